#include "colmap_integration/cli/mesh_command.h"

#include <iostream>

#include "colmap_integration/cli/mosaic_command.h"

namespace lutex {

void AddMeshStageOptions(OptionParser& parser, MeshOptions* options) {
  parser.AddDouble("resolution", &options->surface.resolution,
                   "Grid cell of the height field in model units; 0 (default) = twice the mean spacing of the\n"
                   "      sparse points.");
  parser.AddInt("min-track-length", &options->surface.min_track_length, "Points seen in fewer images are dropped.");
  parser.AddDouble("max-reprojection-error", &options->surface.max_reprojection_error,
                   "Points with a larger mean reprojection error (pixels) are dropped.");
  parser.AddDouble("surface-smoothness", &options->surface.smoothness,
                   "Weight of the height field's bending against the points (higher: smoother).");
}

int RunMeshCommand(int argc, char** argv) {
  MeshOptions options;
  OptionParser parser(
      "lutex mesh --workspace W [--output W/lutex/mesh/mesh.ply] [--resolution S]",
      "Makes a mesh of the scene from W's sparse COLMAP model, on a machine without a GPU (COLMAP's dense\n"
      "stereo needs CUDA). Seafloor surveys are mostly a terrain seen from above: the mesh is a 2.5-D height\n"
      "field fitted to the sparse points. Points seen in few images, with large reprojection errors, under no\n"
      "image or off their local surface are dropped; the heights are a regularised fit on a grid (holes\n"
      "filled smoothly within the images' footprints, nothing outside them), triangulated in the model's\n"
      "frame. The summary says where the points show walls or overhangs that a height field cannot hold.\n"
      "Up: the georeferenced frame's +z (--crs/--enu-origin or W/georef.json), else opposite the cameras'\n"
      "mean viewing direction, or --up-axis. lutex run makes this mesh itself when --mesh is not given\n"
      "(and uses a dense workspace's W/dense/N/meshed-*.ply when there is one).");
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("output", &options.output, "The mesh (.ply; default W/lutex/mesh/mesh.ply).");
  parser.AddString("up-axis", &options.up_axis, "The model's up: x, -x, y, -y, z, -z, or auto (see above).");
  AddGeoreferenceOptions(parser, &options.georeference);
  AddMeshStageOptions(parser, &options);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] { PrintMeshSummary(std::cout, MeshWorkspace(options)); });
  return 0;
}

}  // namespace lutex
