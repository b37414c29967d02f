#pragma once

// `lutex calibrate`: fits the LUT of a camera-and-lights rig from calibration images of targets of known
// colour (targets file, see lib/calibration/targets.h) whose geometry comes from a COLMAP model of the
// calibration images and a mesh of the targets, optionally with pure-water images (beta upper bounds).
//
// Output: the LUT (lut_file.h), `coverage.lut` beside it (alpha = per-node data coverage in [0, 1]),
// `calibration_summary.json` (residuals, iterations, coverage, time) and `slabs/` pictures.

#include <cstddef>
#include <filesystem>
#include <string>

#include "lib/calibration/calibrator.h"
#include "lib/calibration/known_color_sampling.h"
#include "lib/calibration/pure_water_sampling.h"
#include "lib/image/image_io.h"

namespace lutex {

struct CalibrateOptions {
  std::filesystem::path workspace;   // calibration images with their COLMAP model
  std::filesystem::path mesh;        // the targets' geometry, in the model's world frame
  std::filesystem::path targets;     // targets file
  std::filesystem::path pure_water;  // optional: a workspace of pure-water images of the same camera
  std::filesystem::path output;      // the LUT file; empty: W/lutex/calibration/lut.lut
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // LUT grid: cells across and down, slabs, depth range (metres) and spacing.
  int nx = 40, ny = 30, nz = 10;
  double z_near = 0.5, z_far = 5.0;
  // In air: beta fixed at 0 and the reference LUT rendered without water.
  bool in_air = false;
  // The water of the reference LUT that sets the weights: "clear" or "coastal" (ignored in air).
  std::string reference_water = "clear";
  // Where shading puts the light (camera frame, metres): the camera centre (the paper), or a single
  // flash's position. Recorded in the LUT; the reference LUT's point light sits there too.
  Eigen::Vector3d shading_light_in_cam = Eigen::Vector3d::Zero();
  KnownColorSamplingOptions sampling;
  int pure_water_stride = 8;
  PureWaterScreeningOptions pure_water_screening;
  CalibrationOptions calibration;  // levels and weights; grid and in_air are set from the fields above
  int num_threads = 0;

  void Check() const;
};

struct CalibrateSummary {
  std::filesystem::path lut;
  std::size_t num_images = 0;
  std::size_t num_pure_water_images = 0;
  std::size_t num_pure_water_skipped = 0;  // images that seemed to show a surface
  CalibrationSummary calibration;
};

CalibrateSummary CalibrateWorkspace(const CalibrateOptions& options);

}  // namespace lutex
