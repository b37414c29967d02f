#pragma once

// The median of a list of numbers (the upper one of the two middle values for an even count), reordering
// the list in place (linear time, no sort), and the median absolute deviation from a centre. 0 for an
// empty list.

#include <algorithm>
#include <cmath>
#include <vector>

namespace lutex {

template <typename T>
double MedianInPlace(std::vector<T>& values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return static_cast<double>(*middle);
}

template <typename T>
double MedianAbsoluteDeviation(const std::vector<T>& values, double center) {
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (const T value : values) deviations.push_back(std::abs(static_cast<double>(value) - center));
  return MedianInPlace(deviations);
}

}  // namespace lutex
