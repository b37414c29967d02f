#include "lib/calibration/albedo_json.h"

#include <stdexcept>
#include <vector>

#include "lib/image/image_io.h"

namespace lutex {

Eigen::Vector3d ReadAlbedo(const nlohmann::json& object, const std::string& prefix) {
  const bool linear = object.contains(prefix + "_linear");
  if (!linear && !object.contains(prefix + "_srgb8")) {
    throw std::runtime_error("needs " + prefix + "_linear or " + prefix + "_srgb8");
  }
  const std::string key = prefix + (linear ? "_linear" : "_srgb8");
  const auto values = object.at(key).get<std::vector<double>>();
  if (values.size() != 3) throw std::runtime_error(key + " must have 3 values");
  Eigen::Vector3d albedo;
  for (int c = 0; c < 3; ++c) {
    const double limit = linear ? 1.0 : 255.0;
    if (!(values[c] >= 0.0 && values[c] <= limit)) {
      throw std::runtime_error(key + " must be in [0, " + (linear ? std::string("1") : std::string("255")) + "]");
    }
    albedo[c] = linear ? values[c] : SrgbToLinear(values[c] / 255.0);
  }
  return albedo;
}

}  // namespace lutex
