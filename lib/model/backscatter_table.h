#pragma once

// Backscatter depends only on the ray in the camera frame and the range along it, never on the pose: a
// dive computes it once per camera. The table holds, on a grid of pixels every `pixel_stride` pixels
// (plus the last row and column), the cumulative backscatter integral at `num_steps` + 1 ranges spaced
// uniformly in w = log(1 + (s - start) / s0) from `start` to max_range. A lookup interpolates bilinearly between grid
// pixels and linearly in w. Memory: (W / stride + 2) (H / stride + 2) (num_steps + 1) 12 bytes.

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "lib/raycast/camera_rays.h"

namespace lutex {

struct BackscatterTableOptions {
  int pixel_stride = 8;      // grid spacing in pixels
  int num_steps = 256;
  double scale = 0.1;       // s0 [m]
  double max_range = 30.0;  // metres
  double start = 0.0;       // the integral runs from here (metres); zero below it
  int num_threads = 0;
};

class BackscatterTable {
 public:
  // `density(direction_in_cam, s)` is the backscatter integrand at distance s along the unit ray.
  BackscatterTable(const Camera& camera,
                   const std::function<Eigen::Array3d(const Eigen::Vector3d&, double)>& density,
                   const BackscatterTableOptions& options = {});

  // Backscatter seen through pixel (u, v) (continuous pixel coordinates) up to `range` metres.
  Eigen::Vector3d Lookup(double u, double v, double range) const;

 private:
  Eigen::Array3d Cumulative(int grid_col, int grid_row, double range) const;

  BackscatterTableOptions options_;
  int grid_cols_ = 0, grid_rows_ = 0;
  double step_ = 0.0;  // in w
  std::vector<double> grid_u_, grid_v_;
  std::vector<Eigen::Array3f> cumulative_;  // (grid_row * grid_cols + grid_col) * (num_steps + 1) + k
};

}  // namespace lutex
