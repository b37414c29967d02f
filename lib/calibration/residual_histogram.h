#pragma once

// How the residuals of one constraint type are distributed after a solve, per channel: counts in equal
// bins over [-range, range]; residuals beyond the range are counted in the first or last bin, non-finite
// ones not at all. The calibration summary keeps one per constraint type for the report.

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace lutex {

class ResidualHistogram {
 public:
  ResidualHistogram(double range, int num_bins);

  void Add(const Eigen::Vector3d& residual);

  double range() const { return range_; }
  int num_bins() const { return static_cast<int>(counts_[0].size()); }
  // Lower edge of bin `bin` (the upper edge of the last bin is `range`).
  double BinStart(int bin) const { return -range_ + 2.0 * range_ * bin / num_bins(); }
  const std::vector<std::size_t>& counts(int channel) const { return counts_[static_cast<std::size_t>(channel)]; }
  std::size_t total(int channel) const;

 private:
  double range_;
  std::array<std::vector<std::size_t>, 3> counts_;
};

}  // namespace lutex
