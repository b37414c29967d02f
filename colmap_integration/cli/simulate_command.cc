#include "colmap_integration/cli/simulate_command.h"

#include <iomanip>
#include <iostream>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/simulate_workspace.h"

namespace lutex {

int RunSimulateCommand(int argc, char** argv) {
  SimulateOptions options;
  OptionParser parser(
      "lutex simulate --scene SCENE.json --output W [--num-threads N]",
      "Renders a scene description with lutex's physically based simulator (co-moving point or spot lights,\n"
      "water with absorption, scattering and a Henyey-Greenstein phase function, shadows, sensor noise) into\n"
      "a complete COLMAP workspace W with ground truth: images/, sparse/0, scene/mesh.ply,\n"
      "ground_truth/{albedo,depth}/ and ground_truth/true.lut (the LUT a perfect calibration finds).\n"
      "Use it to preview a light rig and water before a dive. Scene format: README, 'Scene descriptions';\n"
      "examples in examples/scenes/.");
  parser.AddPath("scene", &options.scene, "Scene description (JSON).", true);
  parser.AddPath("output", &options.output, "Workspace folder to write.", true);
  AddThreadsOption(parser, &options.num_threads);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    const SimulateSummary summary = SimulateWorkspace(options);
    std::cout << "simulate: " << summary.num_images << " images of " << summary.num_faces << " faces in " << std::fixed
              << std::setprecision(1) << summary.seconds << " s (" << std::setprecision(2) << summary.seconds_per_image
              << " s per image)\n"
              << "  workspace:    " << options.output.string() << "\n"
              << "  images:       " << (options.output / "images").string() << "\n"
              << "  mesh:         " << (options.output / "scene" / "mesh.ply").string() << "\n"
              << "  ground truth: " << (options.output / "ground_truth").string() << "\n";
  });
  return 0;
}

}  // namespace lutex
