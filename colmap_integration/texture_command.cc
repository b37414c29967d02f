#include "colmap_integration/texture_command.h"

#include <iomanip>
#include <iostream>

#include "colmap_integration/option_parser.h"
#include "colmap_integration/texture_workspace.h"

namespace lutex {

int RunTextureCommand(int argc, char** argv) {
  TextureOptions options;
  std::string image_encoding = "srgb8", page_encoding = "srgb8", blend = "fuse";
  double memory_limit_mib = static_cast<double>(options.baking.fusion.memory_limit_bytes >> 20);
  bool no_confidence = false;
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
  parser.AddString("image-encoding", &image_encoding, "Encoding of those images: srgb8 (default), linear16, float.");
  parser.AddPath("confidence", &options.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddFlag("no-confidence", &no_confidence, "Trust every pixel equally.");
  parser.AddPath("output", &options.output, "Textured model: .glb (default W/lutex/model.glb), .gltf, .obj or .ply.");
  parser.AddDouble("texel-size", &options.baking.charts.texel_size,
                   "Texel size in scene units (e.g. 0.001 = 1 mm if the model is in metres), the same at any\n"
                   "range; 0 (default) = the native resolution of each chart's view.");
  parser.AddString("blend", &blend, "fuse (default: robust weighted fusion of all views) or single (one view per face).");
  parser.AddDouble("view-smoothness", &options.baking.selection.smoothness,
                   "Potts weight between adjacent faces from different views (default 0.5; 0 = best view per face).");
  parser.AddInt("max-views-per-face", &options.baking.visibility.max_views_per_face,
                "Best views kept per face for selection and fusion (default 8).");
  parser.AddInt("max-page-size", &options.baking.charts.max_size, "Largest atlas page side in texels (default 8192).");
  parser.AddInt("padding", &options.baking.charts.padding, "Texels around each chart (default 4).");
  parser.AddDouble("memory-limit", &memory_limit_mib,
                   "MiB for the per-texel sample buffers of one pass over the images (default 2048); a larger\n"
                   "atlas is done in several passes.");
  parser.AddString("page-encoding", &page_encoding, "OBJ/PLY pages: srgb8 (default) or linear16 (glTF is always srgb8).");
  parser.AddInt("num-threads", &options.baking.num_threads, "Threads; 0 = all cores. Results do not depend on it.");
  if (!parser.Parse(argc, argv, 2)) return 0;
  options.image_encoding = ParseImageEncoding(image_encoding);
  options.page_encoding = ParseImageEncoding(page_encoding);
  options.baking.fusion.blend = ParseTexelBlend(blend);
  options.use_confidence = !no_confidence;
  if (!(memory_limit_mib >= 1.0)) throw std::invalid_argument("--memory-limit must be at least 1 MiB");
  options.baking.fusion.memory_limit_bytes = static_cast<std::size_t>(memory_limit_mib * 1024.0 * 1024.0);
  const TextureSummary summary = TextureWorkspace(options);
  const TextureBakingSummary& baking = summary.baking;
  std::cout << std::fixed << std::setprecision(1) << "texture: " << baking.num_textured_faces << " of "
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
  for (const auto& path : summary.written) std::cout << "  wrote " << path.string() << "\n";
  return 0;
}

}  // namespace lutex
