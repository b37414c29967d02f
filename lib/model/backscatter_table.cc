#include "lib/model/backscatter_table.h"

#include <algorithm>
#include <cmath>

#include "lib/util/parallel_for.h"

namespace lutex {
namespace {

// Grid coordinates: 0.5, 0.5 + stride, ... and the last pixel centre, so every pixel centre is covered.
std::vector<double> GridCoordinates(std::uint64_t size, int stride) {
  std::vector<double> coordinates;
  for (double c = 0.5; c < static_cast<double>(size) - 0.5; c += stride) coordinates.push_back(c);
  coordinates.push_back(static_cast<double>(size) - 0.5);
  return coordinates;
}

// Index of the interval containing x in sorted `grid`, and the fraction within it.
void Locate(const std::vector<double>& grid, double x, int* index, double* fraction) {
  if (grid.size() == 1) {
    *index = 0;
    *fraction = 0.0;
    return;
  }
  const auto upper = std::upper_bound(grid.begin(), grid.end(), x);
  *index = std::clamp(static_cast<int>(upper - grid.begin()) - 1, 0, static_cast<int>(grid.size()) - 2);
  *fraction = std::clamp((x - grid[*index]) / (grid[*index + 1] - grid[*index]), 0.0, 1.0);
}

}  // namespace

BackscatterTable::BackscatterTable(const Camera& camera,
                                   const std::function<Eigen::Array3d(const Eigen::Vector3d&, double)>& density,
                                   const BackscatterTableOptions& options)
    : options_(options) {
  grid_u_ = GridCoordinates(camera.width, options.pixel_stride);
  grid_v_ = GridCoordinates(camera.height, options.pixel_stride);
  grid_cols_ = static_cast<int>(grid_u_.size());
  grid_rows_ = static_cast<int>(grid_v_.size());
  step_ = std::log1p((options.max_range - options.start) / options.scale) / options.num_steps;
  const std::size_t per_ray = static_cast<std::size_t>(options.num_steps) + 1;
  cumulative_.assign(static_cast<std::size_t>(grid_cols_) * grid_rows_ * per_ray, Eigen::Array3f::Zero());
  ParallelFor(static_cast<std::size_t>(grid_rows_), options.num_threads, [&](std::size_t row) {
    for (int col = 0; col < grid_cols_; ++col) {
      const Eigen::Vector3d ray = camera.CamFromImg(Eigen::Vector2d(grid_u_[col], grid_v_[row]));
      if (!ray.allFinite()) continue;
      const Eigen::Vector3d direction = ray.normalized();
      Eigen::Array3f* values = &cumulative_[(row * grid_cols_ + col) * per_ray];
      Eigen::Array3d sum = Eigen::Array3d::Zero();
      for (int k = 0; k < options.num_steps; ++k) {
        // Midpoint rule in w within each step.
        const double w = (k + 0.5) * step_;
        const double s = options.start + options.scale * std::expm1(w);
        sum += density(direction, s) * options.scale * std::exp(w) * step_;
        values[k + 1] = sum.cast<float>();
      }
    }
  });
}

Eigen::Array3d BackscatterTable::Cumulative(int grid_col, int grid_row, double range) const {
  const double w = std::log1p(std::max(range - options_.start, 0.0) / options_.scale) / step_;
  const int k = std::min(static_cast<int>(w), options_.num_steps - 1);
  const double fraction = std::min(w - k, 1.0);
  const Eigen::Array3f* values =
      &cumulative_[(static_cast<std::size_t>(grid_row) * grid_cols_ + grid_col) * (options_.num_steps + 1)];
  return (1.0 - fraction) * values[k].cast<double>() + fraction * values[k + 1].cast<double>();
}

Eigen::Vector3d BackscatterTable::Lookup(double u, double v, double range) const {
  int col, row;
  double fu, fv;
  Locate(grid_u_, u, &col, &fu);
  Locate(grid_v_, v, &row, &fv);
  const int col1 = std::min(col + 1, grid_cols_ - 1), row1 = std::min(row + 1, grid_rows_ - 1);
  const Eigen::Array3d value = (1 - fu) * (1 - fv) * Cumulative(col, row, range) + fu * (1 - fv) * Cumulative(col1, row, range) +
                               (1 - fu) * fv * Cumulative(col, row1, range) + fu * fv * Cumulative(col1, row1, range);
  return value.matrix();
}

}  // namespace lutex
