#include "lib/model/water.h"

#include <cmath>

namespace lutex {

double HenyeyGreenstein(double cos_angle, double g) {
  const double denominator = 1.0 + g * g - 2.0 * g * cos_angle;
  return (1.0 - g * g) / (4.0 * M_PI * denominator * std::sqrt(denominator));
}

std::optional<Water> WaterPreset(const std::string& name) {
  Water water;
  water.anisotropy_g = 0.9;
  if (name == "clear") {
    water.absorption = Eigen::Vector3d(0.35, 0.05, 0.02);
    water.scattering = Eigen::Vector3d(0.04, 0.045, 0.05);
  } else if (name == "coastal") {
    water.absorption = Eigen::Vector3d(0.45, 0.12, 0.25);
    water.scattering = Eigen::Vector3d(0.35, 0.4, 0.38);
  } else {
    return std::nullopt;
  }
  return water;
}

std::vector<std::string> WaterPresetList() { return {"clear", "coastal"}; }

std::string WaterPresetNames() {
  const std::vector<std::string> names = WaterPresetList();
  std::string joined;
  for (std::size_t i = 0; i < names.size(); ++i) {
    joined += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return joined;
}

}  // namespace lutex
