#include "lib/lut/lut_image_sampler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lutex {

LutImageSampler::LutImageSampler(const FrustumLut& lut, const FrustumLut* coverage) : grid_(lut.grid()) {
  if (coverage && !(coverage->grid() == grid_)) throw std::invalid_argument("the coverage is for another LUT grid");
  // The lower node and the fraction of a coordinate in [0, count - 1], clamped (as FrustumLut::Lookup).
  const auto split = [](double coordinate, int count) {
    if (count <= 1) return Axis{};
    const double clamped = std::clamp(coordinate, 0.0, static_cast<double>(count - 1));
    const int lower = std::min(static_cast<int>(std::floor(clamped)), count - 2);
    return Axis{lower, static_cast<float>(clamped - lower)};
  };
  for (int col = 0; col < grid_.image_width; ++col) {
    columns_.push_back(split((col + 0.5) / grid_.image_width * grid_.nx, grid_.NodesX()));
  }
  for (int row = 0; row < grid_.image_height; ++row) {
    rows_.push_back(split((row + 0.5) / grid_.image_height * grid_.ny, grid_.NodesY()));
  }
  has_coverage_ = coverage != nullptr;
  inverse_square_ = grid_.alpha_interpolation == AlphaInterpolation::kInverseSquare;
  nodes_.resize(static_cast<std::size_t>(grid_.NumNodes()));
  for (int index = 0; index < grid_.NumNodes(); ++index) {
    const int k = index / (grid_.NodesX() * grid_.NodesY());
    const double alpha_factor = inverse_square_ ? grid_.SlabDepth(k) * grid_.SlabDepth(k) : 1.0;
    PackedNode& packed = nodes_[static_cast<std::size_t>(index)];
    for (int c = 0; c < 3; ++c) {
      packed.alpha[c] = static_cast<float>(lut.node(index).alpha[c] * alpha_factor);
      packed.beta[c] = static_cast<float>(lut.node(index).beta[c]);
      packed.coverage[c] = coverage ? static_cast<float>(coverage->node(index).alpha[c]) : 0.0f;
    }
  }
  if (grid_.nz > 1) {
    const bool uniform_z = grid_.spacing == DepthSpacing::kUniformZ;
    depth_offset_ = static_cast<float>(uniform_z ? grid_.z_near : -1.0 / grid_.z_near);
    const double range = uniform_z ? grid_.z_far - grid_.z_near : 1.0 / grid_.z_near - 1.0 / grid_.z_far;
    depth_scale_ = static_cast<float>((grid_.nz - 1) / range);
  }
}

void LutImageSampler::PrepareRow(int row, RowSampler* sampler) const {
  const Axis& y = rows_[static_cast<std::size_t>(row)];
  const int nodes_x = grid_.NodesX(), upper = std::min(y.lower + 1, grid_.NodesY() - 1);
  const int stride_z = nodes_x * grid_.NodesY();
  sampler->image_ = this;
  sampler->nodes_.resize(static_cast<std::size_t>(nodes_x * grid_.nz));
  for (int k = 0; k < grid_.nz; ++k) {
    for (int i = 0; i < nodes_x; ++i) {
      const PackedNode& low = nodes_[static_cast<std::size_t>(k * stride_z + y.lower * nodes_x + i)];
      const PackedNode& high = nodes_[static_cast<std::size_t>(k * stride_z + upper * nodes_x + i)];
      PackedNode& blended = sampler->nodes_[static_cast<std::size_t>(k * nodes_x + i)];
      for (int c = 0; c < 3; ++c) {
        blended.alpha[c] = low.alpha[c] + y.fraction * (high.alpha[c] - low.alpha[c]);
        blended.beta[c] = low.beta[c] + y.fraction * (high.beta[c] - low.beta[c]);
        blended.coverage[c] = low.coverage[c] + y.fraction * (high.coverage[c] - low.coverage[c]);
      }
    }
  }
}

LutPixelSample LutImageSampler::At(int col, int row, float z) const {
  RowSampler sampler;
  PrepareRow(row, &sampler);
  return sampler.At(col, z);
}

}  // namespace lutex
