#include "colmap_integration/texture_command.h"

#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "colmap_integration/image_encoding_option.h"

namespace lutex {

int RunTextureCommand(int argc, char** argv) {
  TextureOptions options;
  OptionParser parser(
      "lutex texture --workspace W --mesh M [--images DIR] [--texel-size S] [--output model.glb]",
      "Bakes one albedo texture for the mesh M from the registered images of the COLMAP workspace W and\n"
      "writes a textured model that map viewers load (GLB by default; .gltf, .obj + .mtl + PNG pages, or a\n"
      "single-page .ply with per-corner texcoords by the output's extension).\n"
      "Steps: which views see each face (exact occlusion from ray casting); one view per face chosen by an\n"
      "MRF (quality = resolution x unoccluded fraction x restoration confidence, Potts smoothness between\n"
      "faces, loopy belief propagation); charts of faces with the same view, projected into it and packed\n"
      "into atlas pages; each texel's colour a robust weighted fusion of every view that sees it (outliers\n"
      "such as particles and highlights rejected), or the chosen view only with --blend single.\n"
      "Images: DIR (default W/lutex/restored from lutex restore, else W/images), confidence maps from\n"
      "DIR_confidence when present. Images are streamed from disk; memory depends on the mesh and the atlas,\n"
      "not on the number of images.");
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("mesh", &options.mesh, "Mesh in the model's world frame.", true);
  parser.AddPath("images", &options.images, "Images to texture from (default W/lutex/restored, else W/images).");
  AddImageEncodingOption(parser, "image-encoding", &options.image_encoding, "How those images are encoded:");
  parser.AddPath("confidence", &options.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddPath("output", &options.output, "Textured model: .glb (default W/lutex/model.glb), .gltf, .obj or .ply.");
  AddImageEncodingOption(parser, "page-encoding", &options.page_encoding,
                         "OBJ/PLY pages (glTF pages are always srgb8):");
  parser.AddInt("num-threads", &options.baking.num_threads, "Threads; 0 = all cores. Results do not depend on it.");
  AddTextureStageOptions(parser, &options);
  if (!parser.Parse(argc, argv, 2)) return 0;
  PrintTextureSummary(std::cout, TextureWorkspace(options));
  return 0;
}

void AddTextureStageOptions(OptionParser& parser, TextureOptions* options) {
  TextureBakingOptions& baking = options->baking;
  parser.AddFlag("no-confidence", &options->ignore_confidence, "Trust every pixel equally.");
  parser.AddDouble("texel-size", &baking.charts.texel_size,
                   "Texel size in scene units (e.g. 0.001 = 1 mm if the model is in metres), the same at any\n"
                   "      range; 0 (default) = the native resolution of each chart's view.");
  parser.AddCustom("blend", "fuse", "fuse (robust weighted fusion of all views) or single (one view per face).",
                   [&baking](const std::string& text) { baking.fusion.blend = ParseTexelBlend(text); });
  parser.AddDouble("view-smoothness", &baking.selection.smoothness,
                   "Potts weight between adjacent faces from different views (0 = best view per face).");
  parser.AddInt("max-views-per-face", &baking.visibility.max_views_per_face,
                "Best views kept per face for selection and fusion.");
  parser.AddInt("max-page-size", &baking.charts.max_size, "Largest atlas page side in texels.");
  parser.AddInt("padding", &baking.charts.padding, "Texels around each chart.");
  parser.AddCustom("memory-limit", std::to_string(baking.fusion.memory_limit_bytes >> 20),
                   "MiB for the per-texel sample buffers of one pass over the images; a larger atlas is done in\n"
                   "      several passes.",
                   [&baking](const std::string& text) {
                     double mib = 0.0;
                     try {
                       mib = std::stod(text);
                     } catch (const std::exception&) {
                     }
                     if (!(mib >= 1.0)) throw std::invalid_argument("--memory-limit must be at least 1 MiB, not '" + text + "'");
                     baking.fusion.memory_limit_bytes = static_cast<std::size_t>(mib * 1024.0 * 1024.0);
                   });
}

void PrintTextureSummary(std::ostream& out, const TextureSummary& summary) {
  const TextureBakingSummary& baking = summary.baking;
  out << std::fixed << std::setprecision(1) << "texture: " << baking.num_textured_faces << " of "
            << baking.num_faces << " faces textured from " << baking.num_views << " images in " << summary.seconds
            << " s\n"
            << "  charts: " << baking.num_charts << " on " << baking.num_pages << " page(s), "
            << double(baking.page_texels) / 1e6 << " Mtexels (" << std::setprecision(0)
            << 100.0 * double(baking.num_texels) / double(std::max<std::size_t>(baking.page_texels, 1))
            << " % on the surface)\n"
            << std::setprecision(2) << "  view selection: energy " << baking.selection.data_cost << " data + "
            << baking.selection.smoothness_cost << " seams (best view per face: "
            << baking.selection.best_view_data_cost << " + " << baking.selection.best_view_smoothness_cost << "), "
            << baking.selection.iterations << " sweeps\n"
            << "  fusion: " << baking.fusion.mean_samples_per_texel << " views per texel, "
            << baking.fusion.rejected_samples << " outlier samples rejected, " << baking.fusion.texels_without_samples
            << " texels seen by no view, " << baking.fusion.num_passes << " pass(es)\n"
            << std::setprecision(2) << "  seams: " << baking.seams.num_seam_edges << " chart-border edges; colour step "
            << 100.0 * baking.seams.seam_step << " % of full scale across them, " << 100.0 * baking.seams.interior_step
            << " % inside charts\n"
            << std::setprecision(1) << "  time: visibility " << baking.seconds_visibility << " s, view selection "
            << baking.seconds_selection << " s, charts and atlas " << baking.seconds_layout << " s, colours "
            << baking.seconds_fusion << " s, writing "
            << summary.seconds - baking.seconds_visibility - baking.seconds_selection - baking.seconds_layout -
                   baking.seconds_fusion
            << " s (incl. reading the mesh)\n"
            << "  images: " << summary.images.string() << "\n"
            << "  confidence: " << (summary.confidence.empty() ? std::string("not used") : summary.confidence.string())
            << "\n";
  for (const auto& path : summary.written) out << "  wrote " << path.string() << "\n";
}

}  // namespace lutex
