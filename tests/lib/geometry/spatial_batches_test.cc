#include "lib/geometry/spatial_batches.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace lutex {
namespace {

// Points on an 8 x 8 grid in the x-y plane, item i at column i % 8 and row i / 8.
std::vector<Eigen::Vector3d> GridPoints() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 64; ++i) points.emplace_back(i % 8, i / 8, 2.0);
  return points;
}

Eigen::AlignedBox3d BoundsOf(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& point : points) bounds.extend(point);
  return bounds;
}

TEST(BatchAlongMortonCurve, WhatFitsInOneBatchStaysInIndexOrder) {
  const std::vector<Eigen::Vector3d> points = GridPoints();
  const std::vector<std::size_t> sizes(points.size(), 3);
  const auto batches = BatchAlongMortonCurve(points, sizes, BoundsOf(points), 64 * 3);
  ASSERT_EQ(batches.size(), 1u);
  ASSERT_EQ(batches[0].size(), 64u);
  for (std::size_t i = 0; i < 64; ++i) EXPECT_EQ(batches[0][i], i);
  EXPECT_TRUE(BatchAlongMortonCurve({}, {}, Eigen::AlignedBox3d(), 10).empty());
}

TEST(BatchAlongMortonCurve, BatchesAreTheQuadrantsOfTheGrid) {
  const std::vector<Eigen::Vector3d> points = GridPoints();
  const std::vector<std::size_t> sizes(points.size(), 1);
  const auto batches = BatchAlongMortonCurve(points, sizes, BoundsOf(points), 16);
  ASSERT_EQ(batches.size(), 4u);
  std::vector<int> seen(64, 0);
  for (const auto& batch : batches) {
    ASSERT_EQ(batch.size(), 16u);
    Eigen::AlignedBox3d box;
    for (const std::size_t item : batch) {
      ++seen[item];
      box.extend(points[item]);
    }
    // A 4 x 4 block of the grid: each batch is one part of the plane, not a stripe across it.
    EXPECT_EQ(box.sizes().x(), 3.0);
    EXPECT_EQ(box.sizes().y(), 3.0);
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int count) { return count == 1; }));
}

TEST(BatchAlongMortonCurve, NoBatchExceedsTheLimitAndALargerItemIsABatchOfItsOwn) {
  const std::vector<Eigen::Vector3d> points = GridPoints();
  std::vector<std::size_t> sizes(points.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) sizes[i] = 1 + (i * 7) % 5;
  sizes[20] = 50;
  const auto batches = BatchAlongMortonCurve(points, sizes, BoundsOf(points), 12);
  std::size_t items = 0;
  for (const auto& batch : batches) {
    std::size_t size = 0;
    for (const std::size_t item : batch) size += sizes[item];
    items += batch.size();
    if (std::find(batch.begin(), batch.end(), 20u) != batch.end()) {
      EXPECT_EQ(batch.size(), 1u);
    } else {
      EXPECT_LE(size, 12u);
    }
  }
  EXPECT_EQ(items, 64u);
  EXPECT_THROW(BatchAlongMortonCurve(points, {1, 2}, BoundsOf(points), 12), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
