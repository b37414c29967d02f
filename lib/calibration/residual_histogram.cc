#include "lib/calibration/residual_histogram.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace lutex {

ResidualHistogram::ResidualHistogram(double range, int num_bins) : range_(range) {
  if (!(range > 0.0) || num_bins < 1) throw std::invalid_argument("ResidualHistogram: range and bins must be positive");
  for (auto& channel : counts_) channel.assign(static_cast<std::size_t>(num_bins), 0);
}

void ResidualHistogram::Add(const Eigen::Vector3d& residual) {
  const int bins = num_bins();
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(residual[c])) continue;
    const double position = (residual[c] + range_) / (2.0 * range_) * bins;
    const int bin = std::clamp(static_cast<int>(std::floor(position)), 0, bins - 1);
    ++counts_[static_cast<std::size_t>(c)][static_cast<std::size_t>(bin)];
  }
}

std::size_t ResidualHistogram::total(int channel) const {
  const auto& channel_counts = counts(channel);
  return std::accumulate(channel_counts.begin(), channel_counts.end(), std::size_t{0});
}

}  // namespace lutex
