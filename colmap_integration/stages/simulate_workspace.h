#pragma once

// `lutex simulate`: renders a scene description (scene_description.h) into a complete COLMAP workspace
// with ground truth, for previewing a rig and water before a dive and for testing:
//
//   W/images/NAME                    the simulated images (8-bit sRGB or 16-bit linear PNG)
//   W/sparse/0/                      COLMAP model with the exact camera and poses (text or binary)
//   W/scene/mesh.ply                 the rendered mesh (with its vertex colours, if any)
//   W/ground_truth/albedo/NAME       true albedo through each pixel centre (16-bit linear PNG, 0 = none)
//   W/ground_truth/depth/NAME.bin    planar depth (COLMAP array, 0 = none)
//   W/ground_truth/true.lut          the LUT a perfect calibration of these images finds (lut_file.h),
//                                    in image units (the sensor's exposure included)
//   W/ground_truth/true_lut_slabs/   its slabs as pictures
//   W/ground_truth/exposure_factors.json  {NAME: each image's exposure relative to the true LUT's} (1
//                                    without the sensor's exposure_variation)

#include <cstddef>
#include <filesystem>

namespace lutex {

struct SimulateOptions {
  // The scene description (JSON).
  std::filesystem::path scene;
  // The workspace to write (created if needed).
  std::filesystem::path output;
  // Threads; <= 0 uses all cores. Results do not depend on it.
  int num_threads = 0;

  void Check() const;
};

struct SimulateSummary {
  std::size_t num_images = 0;
  std::size_t num_faces = 0;
  double seconds = 0.0;
  double seconds_per_image = 0.0;
};

SimulateSummary SimulateWorkspace(const SimulateOptions& options);

}  // namespace lutex
