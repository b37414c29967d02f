#include "colmap_integration/raycast_command.h"

#include <iomanip>
#include <iostream>


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
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("mesh", &options.mesh, "Mesh in the model's world frame (.ply, .obj, .off, .stl).", true);
  parser.AddPath("output", &options.output, "Output folder (default W/lutex/raycast).");
  parser.AddInt("num-threads", &options.num_threads, "Threads; 0 = all cores. Results do not depend on it.");
  parser.AddFlag("previews", &options.write_previews, "Write 8-bit depth and normal previews (--no-previews to skip).");
  if (!parser.Parse(argc, argv, 2)) return 0;
  PrintRaycastSummary(std::cout, RaycastWorkspace(options));
  return 0;
}

void PrintRaycastSummary(std::ostream& out, const RaycastSummary& summary) {
  out << "raycast: " << summary.num_images << " images against " << summary.num_faces << " faces in "
            << std::fixed << std::setprecision(1) << summary.seconds << " s; " << std::setprecision(0)
            << 100.0 * summary.mean_hit_fraction << " % of pixels see the mesh\n"
            << "  depth maps:  " << (summary.output / "depth_maps").string() << "\n"
            << "  normal maps: " << (summary.output / "normal_maps").string() << "\n";
  if (summary.wrote_previews) out << "  previews:    " << (summary.output / "previews").string() << "\n";
}

}  // namespace lutex
