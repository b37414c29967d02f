#include "colmap_integration/cli/tiles_command.h"

#include <iostream>
#include <stdexcept>
#include <string>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/mosaic_command.h"
#include "colmap_integration/cli/texture_command.h"

namespace lutex {

int RunTilesCommand(int argc, char** argv) {
  TilesOptions options;
  OptionParser parser(
      "lutex tiles --workspace W --mesh M [--images DIR] [--crs C --crs-origin E,N,H | --enu-origin LAT,LON,H]\n"
      "       [--tile-faces N] [--image-cache MiB] [--output DIR]",
      "Writes the textured mesh as OGC 3D Tiles 1.1 for web map viewers (CesiumJS and the portals built on\n"
      "it): DIR/tileset.json (default W/lutex/tiles/) and one GLB per tile.\n"
      "The mesh is cut into a quadtree of tiles over its horizontal footprint, each leaf at most --tile-faces\n"
      "faces. Each leaf's views are chosen on the leaf and the surface around it that may hide it, with the\n"
      "views and seam corrections of the leaves done before fixed at its border, so tile borders are not\n"
      "seams; each leaf is baked with those views at full resolution, then each parent from its\n"
      "children's meshes simplified to the same face budget (borders locked, so tiles meet without cracks)\n"
      "at twice their texel size, with a geometric error in metres that tells the viewer when to refine.\n"
      "The georeference (options or W/georef.json) gives the root transform that puts the tiles on the\n"
      "globe; without one the tiles stay in the model's frame and a warning says so. Memory: one leaf and\n"
      "the surface around it at a time; once the tree is made, the mesh waits on disk in the output's\n"
      "temporary folder with the view chosen for each face (about 34 bytes a face) and is read a piece at\n"
      "a time.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("images", &options.views.images, "Images to texture from (default W/lutex/restored, else W/images).");
  AddImageEncodingOption(parser, "image-encoding", &options.views.image_encoding, "How those images are encoded:");
  parser.AddPath("confidence", &options.views.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddPath("output", &options.output, "The tileset's folder (default W/lutex/tiles); replaced when complete.");
  AddTileFacesOption(parser, &options);
  AddThreadsOption(parser, &options.baking.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddImageCacheOption(parser, {&options.picture_cache_bytes});
  AddGeoreferenceOptions(parser, &options.georeference);
  AddBakingOptions(parser, &options.baking, &options.views.ignore_confidence, &options.up_axis);
  AddGltfOptions(parser, &options.gltf);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] { PrintTilesSummary(std::cout, TilesWorkspace(options)); });
  return 0;
}

void AddTileFacesOption(OptionParser& parser, TilesOptions* options) {
  parser.AddCustom("tile-faces", std::to_string(options->tree.max_faces),
                   "Most faces in one tile (the leaves, and each coarser level).", [options](const std::string& text) {
                     std::size_t used = 0;
                     unsigned long long faces = 0;
                     try {
                       faces = std::stoull(text, &used);
                     } catch (const std::exception&) {
                       used = 0;
                     }
                     if (used != text.size() || faces < 1 || faces > 1000000000ULL || text[0] == '-') {
                       throw std::invalid_argument("--tile-faces must be a whole number of faces, at least 1, not '" +
                                                   text + "'");
                     }
                     options->tree.max_faces = static_cast<std::size_t>(faces);
                   });
  parser.NameField("max_faces", "tile-faces");
}

}  // namespace lutex
