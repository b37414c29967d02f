#include "lib/geometry/spatial_batches.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace lutex {

namespace {

// The point's cell of a 1024^3 grid over `bounds`, its three axes' bits interleaved (x highest).
std::uint64_t MortonCode(const Eigen::Vector3d& point, const Eigen::AlignedBox3d& bounds) {
  const Eigen::Vector3d extent = bounds.sizes().cwiseMax(1e-12);
  const Eigen::Vector3d cell =
      ((point - bounds.min()).cwiseQuotient(extent) * 1023.0).cwiseMax(0.0).cwiseMin(1023.0);
  std::uint64_t code = 0;
  for (int bit = 9; bit >= 0; --bit) {
    for (int axis = 0; axis < 3; ++axis) code = (code << 1) | ((static_cast<std::uint64_t>(cell[axis]) >> bit) & 1u);
  }
  return code;
}

}  // namespace

std::vector<std::vector<std::size_t>> BatchAlongMortonCurve(const std::vector<Eigen::Vector3d>& points,
                                                            const std::vector<std::size_t>& sizes,
                                                            const Eigen::AlignedBox3d& bounds,
                                                            std::size_t max_size_per_batch) {
  if (points.size() != sizes.size()) throw std::invalid_argument("spatial batches: one size per point");
  if (points.empty()) return {};
  std::size_t total = 0;
  for (const std::size_t size : sizes) total += size;
  if (total <= max_size_per_batch) {
    std::vector<std::size_t> all(points.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    return {all};
  }
  std::vector<std::pair<std::uint64_t, std::size_t>> order;  // (Morton code, item)
  order.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order.emplace_back(MortonCode(points[i], bounds), i);
  std::sort(order.begin(), order.end());
  std::vector<std::vector<std::size_t>> batches;
  std::size_t size_of_batch = 0;
  for (const auto& [code, item] : order) {
    if (batches.empty() || size_of_batch + sizes[item] > max_size_per_batch) {
      batches.emplace_back();
      size_of_batch = 0;
    }
    batches.back().push_back(item);
    size_of_batch += sizes[item];
  }
  return batches;
}

}  // namespace lutex
