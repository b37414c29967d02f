#include "colmap_integration/cli/raycast_command.h"

#include <iomanip>
#include <iostream>

#include "colmap_integration/cli/dive_options.h"

namespace lutex {

int RunRaycastCommand(int argc, char** argv) {
  RaycastOptions options;
  OptionParser parser(
      "lutex raycast --workspace W --mesh M [--output DIR] [--num-threads N]",
      "Ray-casts the mesh through every pixel centre of every registered image of the COLMAP workspace W\n"
      "and writes per-image planar depth (z in the camera frame) and camera-frame normals in COLMAP's\n"
      "depth/normal map format (0 = no surface), plus 8-bit previews. The mesh must be in the sparse\n"
      "model's world frame. All camera models of COLMAP 3.8-4.x are supported, distorted ones included.\n"
      "Output files: DIR/depth_maps/NAME.geometric.bin, DIR/normal_maps/NAME.geometric.bin,\n"
      "DIR/previews/NAME.{depth,normal}.png; DIR defaults to W/lutex/raycast.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("output", &options.output, "Output folder (default W/lutex/raycast).");
  AddThreadsOption(parser, &options.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  parser.AddFlag("previews", &options.write_previews, "Write 8-bit depth and normal previews (--no-previews to skip).");
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    PrintRaycastSummary(std::cout, RaycastWorkspace(options));
  });
  return 0;
}

}  // namespace lutex
