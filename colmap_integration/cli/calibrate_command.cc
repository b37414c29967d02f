#include "colmap_integration/cli/calibrate_command.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <iostream>
#include <vector>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/io/workspace.h"

namespace lutex {

namespace {

// "x,y,z" (or, when `scalar_allowed`, one value for all three).
Eigen::Vector3d ParseVector3(std::string text, const std::string& option, bool scalar_allowed) {
  std::replace(text.begin(), text.end(), ',', ' ');
  std::istringstream fields(text);
  std::vector<double> values;
  double value;
  while (fields >> value) values.push_back(value);
  if (!fields.eof() || !(values.size() == 3 || (scalar_allowed && values.size() == 1))) {
    throw std::invalid_argument(option + " expects " + (scalar_allowed ? "a number or " : "") + "x,y,z");
  }
  return values.size() == 1 ? Eigen::Vector3d::Constant(values[0]) : Eigen::Vector3d(values[0], values[1], values[2]);
}

}  // namespace

void AddCalibrateStageOptions(OptionParser& parser, CalibrateOptions* options) {
  parser.AddPath("targets", &options->targets, "Targets file (JSON).");
  parser.AddPath("targets-workspace", &options->targets_workspace, "Separate calibration images of the targets.");
  parser.AddPath("targets-mesh", &options->targets_mesh, "Mesh of the targets in W2's world frame.");
  parser.AddPath("chessboard", &options->chessboard,
                 "Board file (JSON; README): a chessboard (inner corners, square size, black and white albedo)\n"
                 "      or a ChArUco board with coloured patches (squares, sizes, dictionary, patches).");
  parser.AddPath("chessboard-images", &options->chessboard_images,
                 "Folder of images of the board, taken with W's camera (no model or mesh needed).");
  parser.AddFlag("correspondences", &options->correspondences, "Correspondence constraints from W's images.");
  parser.AddCustom("grey-world", "", "Without targets: mean albedo V or r,g,b of the surveyed surfaces.",
                   [options](const std::string& text) {
                     options->calibration.grey_world_albedo = ParseVector3(text, "--grey-world", true);
                   });
  parser.NameField("calibration.grey_world_albedo", "grey-world");
  parser.NameField("grey_world_albedo", "grey-world");
  parser.AddInt("superpixels", &options->correspondence_extraction.superpixels.count,
                "Superpixels per image for correspondences (paper: 300).");
  parser.AddInt("partners", &options->correspondence_extraction.partners,
                "Views each superpixel is matched in, at most.");
  parser.AddPath("pure-water", &options->pure_water, "Workspace of pure-water images (optional).");
  parser.AddFlag("trust-pure-water", &options->trust_pure_water,
                 "Use every pure-water image, also those that seem to show a surface (a warning says why).");
  parser.AddFlag("in-air", &options->calibration.in_air, "No water: backscatter fixed at 0.");
  parser.AddString("reference-water", &options->reference_water,
                   "The water the fit starts from: auto, clear or coastal. Its attenuations are fitted to\n"
                   "      the observations (README, 'The water prior'); the preset shapes backscatter and bounds\n"
                   "      how much forward scattering is taken out. auto fits from clear water, measures how\n"
                   "      much the water scatters (printed) and fits again from the preset nearest that; without\n"
                   "      known colours (--targets or --chessboard) it keeps the clear water.");
  parser.AddFlag("remove-forward-scatter", &options->remove_forward_scatter,
                 "Take forward scattering (light from the surface scattered on its way to the camera, which\n"
                 "      blurs the lit centre over the image: turbid water's veil) out of every image before\n"
                 "      fitting (README, 'Forward scattering'): the reference water's, or less where a first fit\n"
                 "      measures the water to scatter less (printed). Recorded in the LUT; lutex restore takes\n"
                 "      out the same. In turbid water it brings the Blender seafloor from 7.7 to 5.7 pp, in clear\n"
                 "      water from 1.8 to 1.4. --no-remove-forward-scatter keeps it: in clear water one fit\n"
                 "      instead of two, and restoration 2.9 s faster per 12 MP image. Ignored --in-air.");
  parser.AddInt("lut-nx", &options->calibration.grid.nx, "LUT cells across the image (levels: a tenth, a half, all).");
  parser.AddInt("lut-ny", &options->calibration.grid.ny, "LUT cells down the image.");
  parser.AddInt("lut-nz", &options->calibration.grid.nz, "LUT slabs in depth.");
  for (const char* axis : {"nx", "ny", "nz"}) parser.NameField(std::string("calibration.grid.") + axis, std::string("lut-") + axis);
  parser.AddCustom("shading-light", "0,0,0",
                   "x,y,z in the camera frame (metres) where shading puts the light: the camera centre (the paper),\n"
                   "      or a single flash's position. Recorded in the LUT; lutex restore follows it.",
                   [options](const std::string& text) {
                     options->calibration.grid.shading.light_in_cam = ParseVector3(text, "--shading-light", false);
                   });
  parser.AddPath("shading-rig", &options->shading_rig,
                   "A JSON file with the lights of the rig, \"lights\": [...] as in a scene description\n"
                   "      (positions, axes, beam profiles, powers). Shading then weighs each light by the irradiance\n"
                   "      it gives the point, so alpha no longer depends on the surface's tilt where one light\n"
                   "      dominates (README, 'Shading'). Replaces --shading-light; recorded in the LUT.");
  parser.AddFlag("fit-rig", &options->fit_rig,
                 "Without --shading-rig or --shading-light: fit the rig to the observations (in water lights\n"
                 "      beside the camera and their beams, in air where the flash is) and shade with it, as if\n"
                 "      given (README, 'The water prior'); recorded in the LUT. --no-fit-rig shades from the\n"
                 "      camera centre instead.");
  parser.AddString("exposure-gains", &options->exposure_gains,
                   "Fit one exposure gain per image (strobes whose power varies, auto exposure), divide it out\n"
                   "      and fit the LUT again: auto (with --correspondences and known colours), fit (with\n"
                   "      --correspondences, also without known colours: check the gains it reports) or none.\n"
                   "      The gains go to exposure.json beside the LUT and lutex restore applies them. EXIF\n"
                   "      exposure (t * ISO / N^2) applies in every case (README, 'Exposure').");
    parser.AddDouble("smoothness", &options->calibration.smoothness_scale,
                   "Smoothness weight relative to observations (paper: 0.01); lutex multiplies it per channel by\n"
                   "      the channel's mean observed intensity over the brightest channel's, so a dark channel is\n"
                   "      not regularised harder than a bright one.");
  parser.AddDouble("z-near", &options->calibration.grid.z_near, "Nearest slab's planar depth (scene units).");
  parser.AddDouble("z-far", &options->calibration.grid.z_far, "Farthest slab's planar depth.");
}

int RunCalibrateCommand(int argc, char** argv) {
  CalibrateOptions options;
  OptionParser parser(
      "lutex calibrate --workspace W --mesh M [--targets T.json [--targets-workspace W2 --targets-mesh M2]]\n"
      "                [--correspondences [--grey-world V]] [--pure-water W3] [--in-air] [--output L]",
      "Fits the lookup table of light-and-water effects (alpha, beta per voxel and channel). W is a COLMAP\n"
      "workspace and M a mesh of its scene in the model's world frame. Constraints:\n"
      "  --targets T: targets of known colour (planar polygons with their albedo; README, 'Targets'), seen in\n"
      "    W's images, or in separate calibration images W2 of the same camera with their own mesh M2.\n"
      "  --correspondences: the same surface seen by several of W's images restores to the same albedo\n"
      "    (SLIC superpixels matched across views). With targets they fill what the targets did not reach;\n"
      "    without, they fix the LUT up to a factor per channel, which --grey-world V sets (V: the mean albedo\n"
      "    of the surveyed surfaces, e.g. 0.3, or r,g,b).\n"
      "  --chessboard C --chessboard-images DIR: a black-and-white chessboard of known albedo (paper Sec. 4.3)\n"
      "    or a ChArUco board with coloured patches, found by OpenCV in DIR's images (same camera as W) and\n"
      "    posed by solvePnP.\n"
      "  --pure-water W3: images of the same camera looking into empty water bound the backscatter.\n"
      "Writes the LUT L (default W/lutex/calibration/lut.lut), coverage.lut, calibration_summary.json and\n"
      "slab pictures beside it.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("output", &options.output, "LUT file to write (default W/lutex/calibration/lut.lut).");
  AddImageEncodingOption(parser, "input-encoding", &options.input_encoding, "How W's images are encoded:");
  AddThreadsOption(parser, &options.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddCalibrateStageOptions(parser, &options);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    const CalibrateSummary summary = CalibrateWorkspace(options);
    PrintCalibrateSummary(std::cout, summary);
  });
  return 0;
}

}  // namespace lutex
