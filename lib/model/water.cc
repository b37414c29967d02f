#include "lib/model/water.h"

#include <cmath>

namespace lutex {

double HenyeyGreenstein(double cos_angle, double g) {
  const double denominator = 1.0 + g * g - 2.0 * g * cos_angle;
  return (1.0 - g * g) / (4.0 * M_PI * denominator * std::sqrt(denominator));
}

}  // namespace lutex
