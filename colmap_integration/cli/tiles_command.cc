#include "colmap_integration/cli/tiles_command.h"

#include <iostream>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/mosaic_command.h"
#include "colmap_integration/cli/texture_command.h"
#include "colmap_integration/stages/tiles_workspace.h"

namespace lutex {

int RunTilesCommand(int argc, char** argv) {
  TilesOptions options;
  OptionParser parser(
      "lutex tiles --workspace W --mesh M [--images DIR] [--crs C --crs-origin E,N,H | --enu-origin LAT,LON,H]\n"
      "       [--tile-faces N] [--output DIR]",
      "Writes the textured mesh as OGC 3D Tiles 1.1 for web map viewers (CesiumJS and the portals built on\n"
      "it): DIR/tileset.json (default W/lutex/tiles/) and one GLB per tile.\n"
      "The mesh is cut into a quadtree of tiles over its horizontal footprint, each leaf at most --tile-faces\n"
      "faces. One view per face is chosen for the whole mesh (as lutex texture does), so tile borders are\n"
      "not seams; each leaf is baked with those views at full resolution, then each parent from its\n"
      "children's meshes simplified to the same face budget (borders locked, so tiles meet without cracks)\n"
      "at twice their texel size, with a geometric error in metres that tells the viewer when to refine.\n"
      "The georeference (options or W/georef.json) gives the root transform that puts the tiles on the\n"
      "globe; without one the tiles stay in the model's frame and a warning says so. Memory: one tile at a\n"
      "time, plus the view chosen for every face.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("images", &options.views.images, "Images to texture from (default W/lutex/restored, else W/images).");
  AddImageEncodingOption(parser, "image-encoding", &options.views.image_encoding, "How those images are encoded:");
  parser.AddPath("confidence", &options.views.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddPath("output", &options.output, "The tileset's folder (default W/lutex/tiles); replaced when complete.");
  int tile_faces = static_cast<int>(options.tree.max_faces);
  parser.AddIntInRange("tile-faces", &tile_faces, 1, 100000000, "Most faces in one tile (leaves, and each coarser level).");
  parser.NameField("max_faces", "tile-faces");
  AddThreadsOption(parser, &options.baking.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddGeoreferenceOptions(parser, &options.georeference);
  AddBakingOptions(parser, &options.baking, &options.views.ignore_confidence, &options.up_axis);
  if (!parser.Parse(argc, argv, 2)) return 0;
  options.tree.max_faces = static_cast<std::size_t>(tile_faces);
  parser.RunWithFlags([&] { PrintTilesSummary(std::cout, TilesWorkspace(options)); });
  return 0;
}

}  // namespace lutex
