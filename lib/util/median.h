#pragma once

// The median of a list of numbers (the upper one of the two middle values for an even count), reordering
// the list in place (linear time, no sort). 0 for an empty list.

#include <algorithm>
#include <vector>

namespace lutex {

template <typename T>
double MedianInPlace(std::vector<T>& values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return static_cast<double>(*middle);
}

}  // namespace lutex
