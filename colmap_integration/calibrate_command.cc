#include "colmap_integration/calibrate_command.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <iostream>

#include "colmap_integration/calibrate_workspace.h"
#include "colmap_integration/option_parser.h"

namespace lutex {

int RunCalibrateCommand(int argc, char** argv) {
  CalibrateOptions options;
  std::string input_encoding = "srgb8";
  OptionParser parser(
      "lutex calibrate --workspace W --mesh M --targets T.json [--pure-water W2] [--in-air] [--output L]",
      "Fits the lookup table of light-and-water effects (alpha, beta per voxel and channel) from calibration\n"
      "images of targets of known colour. W is a COLMAP workspace of the calibration images, M a mesh of the\n"
      "targets in its world frame, T the targets file (planar polygons with their albedo; README, 'Targets').\n"
      "Optional pure-water images (a workspace W2 of the same camera looking into empty water) bound the\n"
      "backscatter from above. Writes the LUT L (default W/lutex/calibration/lut.lut), coverage.lut,\n"
      "calibration_summary.json and slab pictures beside it.");
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace of the calibration images.", true);
  parser.AddPath("mesh", &options.mesh, "Mesh of the targets in the model's world frame.", true);
  parser.AddPath("targets", &options.targets, "Targets file (JSON).", true);
  parser.AddPath("pure-water", &options.pure_water, "Workspace of pure-water images (optional).");
  parser.AddPath("output", &options.output, "LUT file to write (default W/lutex/calibration/lut.lut).");
  parser.AddString("input-encoding", &input_encoding, "srgb8, linear16 or float.");
  parser.AddFlag("in-air", &options.in_air, "No water: backscatter fixed at 0.");
  parser.AddString("reference-water", &options.reference_water, "Water of the weighting LUT: clear or coastal.");
  parser.AddInt("lut-nx", &options.nx, "LUT cells across the image (levels: a tenth, a half, all).");
  parser.AddInt("lut-ny", &options.ny, "LUT cells down the image.");
  parser.AddInt("lut-nz", &options.nz, "LUT slabs in depth.");
  parser.AddInt("num-threads", &options.num_threads, "Threads; 0 = all cores. Results do not depend on it.");
  std::string shading_light = "0,0,0";
  parser.AddString("shading-light", &shading_light,
                   "x,y,z in the camera frame (metres) where shading puts the light: the camera centre (the paper),\n"
                   "      or a single flash's position. Recorded in the LUT; lutex restore follows it.");
  parser.AddDouble("smoothness", &options.calibration.smoothness_scale,
                   "Smoothness weight relative to observations (paper: 0.01).");
  parser.AddDouble("z-near", &options.z_near, "Nearest slab's planar depth (scene units).");
  parser.AddDouble("z-far", &options.z_far, "Farthest slab's planar depth.");
  if (!parser.Parse(argc, argv, 2)) return 0;
  options.input_encoding = ParseImageEncoding(input_encoding);
  {
    std::replace(shading_light.begin(), shading_light.end(), ',', ' ');
    std::istringstream fields(shading_light);
    if (!(fields >> options.shading_light_in_cam.x() >> options.shading_light_in_cam.y() >> options.shading_light_in_cam.z())) {
      throw std::invalid_argument("--shading-light expects x,y,z");
    }
  }
  const CalibrateSummary summary = CalibrateWorkspace(options);
  const CalibrationSummary& c = summary.calibration;
  std::cout << std::fixed << std::setprecision(4) << "calibrate: " << summary.num_images << " images, "
            << c.num_known_color << " known-colour and " << c.num_pure_water << " pure-water observations ("
            << summary.num_pure_water_images << " pure-water images, " << summary.num_pure_water_skipped
            << " skipped as showing a surface); "
            << "residual RMS " << c.known_color_rms.x() << " " << c.known_color_rms.y() << " " << c.known_color_rms.z()
            << "; " << std::setprecision(0) << 100 * c.covered_fraction << " % of nodes covered; "
            << std::setprecision(1) << c.seconds << " s\n"
            << "  LUT:      " << summary.lut.string() << "\n"
            << "  coverage: " << (summary.lut.parent_path() / "coverage.lut").string() << "\n";
  return 0;
}

}  // namespace lutex
