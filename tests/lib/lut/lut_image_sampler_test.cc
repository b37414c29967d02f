#include "lib/lut/lut_image_sampler.h"

#include <random>

#include <gtest/gtest.h>

namespace lutex {
namespace {

FrustumLut RandomLut(const FrustumLutGrid& grid, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(0.05, 1.0);
  FrustumLut lut(grid);
  for (int index = 0; index < grid.NumNodes(); ++index) {
    for (int c = 0; c < 3; ++c) {
      lut.node(index).alpha[c] = value(random);
      lut.node(index).beta[c] = 0.1 * value(random);
    }
  }
  return lut;
}

FrustumLutGrid Grid(int nz, DepthSpacing spacing, AlphaInterpolation interpolation) {
  FrustumLutGrid grid;
  grid.nx = 7;
  grid.ny = 5;
  grid.nz = nz;
  grid.z_near = 0.4;
  grid.z_far = 3.0;
  grid.spacing = spacing;
  grid.alpha_interpolation = interpolation;
  grid.image_width = 321;
  grid.image_height = 203;
  return grid;
}

// Every pixel-centre lookup agrees with FrustumLut::Lookup (the reference, tested against linear
// functions) to float precision, for both depth spacings, both alpha interpolations, one slab, and depths
// in front of, inside and beyond the depth range.
TEST(LutImageSampler, AgreesWithTheLutsOwnLookup) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> depth(0.1, 5.0);
  for (const int nz : {1, 2, 6}) {
    for (const DepthSpacing spacing : {DepthSpacing::kUniformZ, DepthSpacing::kUniformInverseZ}) {
      for (const AlphaInterpolation interpolation : {AlphaInterpolation::kTrilinear, AlphaInterpolation::kInverseSquare}) {
        const FrustumLut lut = RandomLut(Grid(nz, spacing, interpolation), 11);
        const LutImageSampler sampler(lut);
        for (int trial = 0; trial < 2000; ++trial) {
          const int col = static_cast<int>(random() % 321), row = static_cast<int>(random() % 203);
          const double z = depth(random);
          const LutNode expected = lut.Lookup(col + 0.5, row + 0.5, z);
          const LutPixelSample actual = sampler.At(col, row, static_cast<float>(z));
          for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(actual.alpha[c], expected.alpha[c], 2e-5 * expected.alpha[c]) << nz << " slabs, z " << z;
            ASSERT_NEAR(actual.beta[c], expected.beta[c], 2e-5 * expected.beta[c]) << nz << " slabs, z " << z;
            ASSERT_EQ(actual.coverage[c], 1.0f);
          }
        }
      }
    }
  }
}

// Coverage interpolates trilinearly (a fraction does not fall off like 1/z^2) even on an inverse-square
// grid: equal to a trilinear lookup of the same node values.
TEST(LutImageSampler, InterpolatesCoverageTrilinearly) {
  const FrustumLutGrid grid = Grid(6, DepthSpacing::kUniformInverseZ, AlphaInterpolation::kInverseSquare);
  const FrustumLut lut = RandomLut(grid, 5);
  const FrustumLut coverage = RandomLut(grid, 9);
  FrustumLutGrid trilinear_grid = grid;
  trilinear_grid.alpha_interpolation = AlphaInterpolation::kTrilinear;
  FrustumLut coverage_trilinear(trilinear_grid);
  for (int index = 0; index < grid.NumNodes(); ++index) coverage_trilinear.node(index) = coverage.node(index);
  const LutImageSampler sampler(lut, &coverage);
  for (int row = 0; row < 203; row += 7) {
    for (int col = 0; col < 321; col += 5) {
      const double z = 0.3 + 0.01 * (row + col);
      const Eigen::Vector3d expected = coverage_trilinear.Lookup(col + 0.5, row + 0.5, z).alpha;
      const LutPixelSample actual = sampler.At(col, row, static_cast<float>(z));
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(actual.coverage[c], expected[c], 2e-6);
    }
  }
  // Fully covered stays exactly covered between slabs.
  FrustumLut full(grid);
  for (int index = 0; index < grid.NumNodes(); ++index) full.node(index).alpha.setOnes();
  const LutImageSampler covered(lut, &full);
  EXPECT_NEAR(covered.At(100, 100, 1.234f).coverage[1], 1.0f, 1e-6);
}

TEST(LutImageSampler, RejectsCoverageOfAnotherGrid) {
  const FrustumLut lut = RandomLut(Grid(6, DepthSpacing::kUniformZ, AlphaInterpolation::kTrilinear), 1);
  const FrustumLut other = RandomLut(Grid(5, DepthSpacing::kUniformZ, AlphaInterpolation::kTrilinear), 1);
  EXPECT_THROW(LutImageSampler(lut, &other), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
