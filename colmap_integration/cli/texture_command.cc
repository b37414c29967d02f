#include "colmap_integration/cli/texture_command.h"

#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/mosaic_command.h"

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
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("images", &options.views.images, "Images to texture from (default W/lutex/restored, else W/images).");
  AddImageEncodingOption(parser, "image-encoding", &options.views.image_encoding, "How those images are encoded:");
  parser.AddPath("confidence", &options.views.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddPath("output", &options.output, "Textured model: .glb (default W/lutex/model.glb), .gltf, .obj or .ply.");
  AddImageEncodingOption(parser, "page-encoding", &options.page_encoding,
                         "OBJ/PLY pages (glTF pages are always srgb8):");
  AddThreadsOption(parser, &options.baking.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddGeoreferenceOptions(parser, &options.georeference);
  AddTextureStageOptions(parser, &options);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    PrintTextureSummary(std::cout, TextureWorkspace(options));
  });
  return 0;
}

void AddTextureStageOptions(OptionParser& parser, TextureOptions* options) {
  AddBakingOptions(parser, &options->baking, &options->views.ignore_confidence, &options->up_axis);
  AddGltfOptions(parser, &options->gltf);
}

void AddGltfOptions(OptionParser& parser, GltfOptions* gltf) {
  parser.AddFlag("meshopt-compression", &gltf->meshopt_compression,
                 "Compress the GLB's geometry losslessly with EXT_meshopt_compression (CesiumJS, three.js with\n"
                 "      its MeshoptDecoder, Babylon.js and gltfpack read it; viewers without a decoder refuse the\n"
                 "      file). Positions, normals, texture coordinates and indices shrink to 35-60 % of their size;\n"
                 "      the PNG texture pages, most of a textured model's bytes, do not change.");
}

void AddBakingOptions(OptionParser& parser, TextureBakingOptions* baking_options, bool* ignore_confidence,
                      std::string* up_axis) {
  TextureBakingOptions& baking = *baking_options;
  parser.AddFlag("no-confidence", ignore_confidence, "Trust every pixel equally.");
  parser.AddString("up-axis", up_axis,
                   "The model's up for the GLB (glTF is +Y up): x, -x, y, -y, z, -z, or auto = opposite the\n"
                   "      cameras' mean viewing direction (snapped to an axis within 10 degrees).");
  parser.AddDouble("texel-size", &baking.charts.texel_size,
                   "Texel size in scene units (e.g. 0.001 = 1 mm if the model is in metres), the same at any\n"
                   "      range; 0 (default) = the native resolution of each chart's view.");
  AddViewFusionOptions(parser, &baking);
  parser.AddInt("max-page-size", &baking.charts.max_size, "Largest atlas page side in texels.");
  parser.NameField("max_size", "max-page-size");
  parser.AddInt("padding", &baking.charts.padding, "Texels around each chart.");
  parser.AddCustom("fusion-memory", std::to_string(baking.fusion.memory_limit_bytes >> 20),
                   "MiB for the texel table and per-texel sample buffers of one pass over the images; a larger\n"
                   "      atlas is coloured in several passes, each over a part of the surface.",
                   [&baking](const std::string& text) {
                     baking.fusion.memory_limit_bytes = ParseMebibytes("fusion-memory", text);
                   });
}

void AddViewFusionOptions(OptionParser& parser, TextureBakingOptions* baking) {
  parser.AddCustom("blend", "fuse", "fuse (robust weighted fusion of all views) or single (one view per face).",
                   [baking](const std::string& text) { baking->fusion.blend = ParseTexelBlend(text); });
  parser.AddDouble("view-smoothness", &baking->selection.smoothness,
                   "Potts weight between adjacent faces from different views (0 = best view per face).");
  parser.AddInt("max-views-per-face", &baking->visibility.max_views_per_face,
                "Best views kept per face for selection and fusion.");
  parser.AddFlag("seam-levelling", &baking->levelling.enabled,
                 "Level the colours where charts of different images meet (Lempitsky & Ivanov): a smooth\n"
                 "      correction per vertex and image, solved over the whole mesh; --no-seam-levelling: off.");
}

}  // namespace lutex
