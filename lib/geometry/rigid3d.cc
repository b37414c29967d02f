#include "lib/geometry/rigid3d.h"

#include <cmath>

namespace lutex {

bool Rigid3d::IsValid() const {
  return rotation.coeffs().allFinite() && translation.allFinite() &&
         std::abs(rotation.norm() - 1.0) < 1e-6;
}

}  // namespace lutex
