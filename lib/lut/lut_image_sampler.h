#pragma once

// FrustumLut lookups at the pixel centres of a whole image, for restoration (every pixel of every image
// of a dive). Gives the same values as FrustumLut::Lookup(col + 0.5, row + 0.5, z) to float precision,
// several times faster: the interpolation weights across the image depend only on the column and the
// row, so they are computed once per column and once per row; the nodes are interpolated between LUT
// rows once per image row (RowSampler); node values are packed as floats
// (alpha premultiplied by its slab's z^2 for AlphaInterpolation::kInverseSquare); and the data coverage of
// the same grid is interpolated in the same pass, sharing the weights.
//
// Coverage is interpolated trilinearly (weights summing to 1), whatever the grid's alpha interpolation:
// it is a fraction, not a quantity that falls off with distance.

#include <algorithm>
#include <array>
#include <vector>

#include "lib/lut/frustum_lut.h"

namespace lutex {

struct LutPixelSample {
  std::array<float, 3> alpha{};
  std::array<float, 3> beta{};
  std::array<float, 3> coverage{};  // exactly 1 when the sampler has no coverage
};

class LutImageSampler {
 private:
  struct PackedNode {
    std::array<float, 3> alpha;  // alpha, times the slab's z^2 for inverse-square interpolation
    std::array<float, 3> beta;
    std::array<float, 3> coverage;
  };

 public:
  // The LUT along one image row, prepared by PrepareRow: the nodes interpolated between the two LUT rows
  // around the image row, for every LUT column and slab, so that each pixel interpolates four nodes
  // instead of eight. Reuse one for every row of an image.
  class RowSampler {
   public:
    // The LUT at the centre of pixel (col, row of the prepared row), col < grid().image_width, and
    // planar depth z (metres, camera frame).
    LutPixelSample At(int col, float z) const;

   private:
    friend class LutImageSampler;
    const LutImageSampler* image_ = nullptr;
    std::vector<PackedNode> nodes_;  // slab k, LUT column i at k * NodesX() + i
  };

  // `coverage` optional: a LUT on the same grid whose alpha holds per-node coverage in [0, 1]. Throws
  // std::invalid_argument if its grid differs.
  explicit LutImageSampler(const FrustumLut& lut, const FrustumLut* coverage = nullptr);

  // Prepares image row `row` < grid().image_height in `sampler`.
  void PrepareRow(int row, RowSampler* sampler) const;

  // One pixel (prepares its row: for scattered lookups; restoring an image goes row by row).
  LutPixelSample At(int col, int row, float z) const;

 private:
  struct Axis {
    int lower = 0;         // lower node index
    float fraction = 0.f;  // towards the upper node
  };

  FrustumLutGrid grid_;
  std::vector<Axis> columns_;  // per image column
  std::vector<Axis> rows_;     // per image row
  std::vector<PackedNode> nodes_;
  bool has_coverage_ = false;
  bool inverse_square_ = false;
  // SlabCoordinate(z) = clamp((depth_term(z) - depth_offset_) * depth_scale_, 0, nz - 1), depth_term
  // being z or -1/z by the grid's spacing.
  float depth_offset_ = 0.f;
  float depth_scale_ = 0.f;
};

// Inline: restoration calls it for every pixel of every image.
inline LutPixelSample LutImageSampler::RowSampler::At(int col, float z) const {
  const LutImageSampler& image = *image_;
  const FrustumLutGrid& grid = image.grid_;
  const Axis& x = image.columns_[static_cast<std::size_t>(col)];
  const float depth_term = grid.spacing == DepthSpacing::kUniformZ ? z : -1.0f / std::max(z, 1e-12f);
  const float slab = std::clamp((depth_term - image.depth_offset_) * image.depth_scale_, 0.0f, static_cast<float>(grid.nz - 1));
  const int k0 = std::min(static_cast<int>(slab), std::max(grid.nz - 2, 0));
  const float fz = slab - static_cast<float>(k0);
  const int k1 = std::min(k0 + 1, grid.nz - 1);

  const int nodes_x = grid.NodesX();
  const std::array<const PackedNode*, 4> corner = {
      &nodes_[static_cast<std::size_t>(k0 * nodes_x + x.lower)], &nodes_[static_cast<std::size_t>(k0 * nodes_x + x.lower + 1)],
      &nodes_[static_cast<std::size_t>(k1 * nodes_x + x.lower)], &nodes_[static_cast<std::size_t>(k1 * nodes_x + x.lower + 1)]};
  const float wx0 = 1.0f - x.fraction, wz0 = 1.0f - fz;
  const std::array<float, 4> weight = {wx0 * wz0, x.fraction * wz0, wx0 * fz, x.fraction * fz};
  LutPixelSample sample;
  sample.coverage = image.has_coverage_ ? std::array<float, 3>{0.f, 0.f, 0.f} : std::array<float, 3>{1.f, 1.f, 1.f};
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      sample.alpha[c] += weight[k] * corner[k]->alpha[c];
      sample.beta[c] += weight[k] * corner[k]->beta[c];
      if (image.has_coverage_) sample.coverage[c] += weight[k] * corner[k]->coverage[c];
    }
  }
  if (image.inverse_square_) {
    const float clamped_z = grid.nz == 1 ? static_cast<float>(grid.z_near)
                                         : std::clamp(z, static_cast<float>(grid.z_near), static_cast<float>(grid.z_far));
    const float inverse_z2 = 1.0f / (clamped_z * clamped_z);
    for (float& alpha : sample.alpha) alpha *= inverse_z2;
  }
  return sample;
}

}  // namespace lutex
