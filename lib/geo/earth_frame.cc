#include "lib/geo/earth_frame.h"

#include <cmath>

namespace lutex {

Eigen::Vector3d EcefFromGeodetic(const Eigen::Vector3d& latitude_longitude_height) {
  // WGS 84: semi-major axis and flattening.
  constexpr double kA = 6378137.0;
  constexpr double kF = 1.0 / 298.257223563;
  constexpr double kE2 = kF * (2.0 - kF);
  const double latitude = latitude_longitude_height.x() * M_PI / 180.0;
  const double longitude = latitude_longitude_height.y() * M_PI / 180.0;
  const double height = latitude_longitude_height.z();
  const double sin_latitude = std::sin(latitude);
  const double prime_vertical = kA / std::sqrt(1.0 - kE2 * sin_latitude * sin_latitude);
  return Eigen::Vector3d((prime_vertical + height) * std::cos(latitude) * std::cos(longitude),
                         (prime_vertical + height) * std::cos(latitude) * std::sin(longitude),
                         (prime_vertical * (1.0 - kE2) + height) * sin_latitude);
}

Eigen::Matrix4d EcefFromModelNear(const MapFrame& frame, const Eigen::Vector3d& point_in_model) {
  const auto ecef_at = [&](const Eigen::Vector3d& point) { return EcefFromGeodetic(frame.GeodeticFromModel(point)); };
  Eigen::Matrix3d axes;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d step = Eigen::Vector3d::Unit(k);
    axes.col(k) = 0.5 * (ecef_at(point_in_model + step) - ecef_at(point_in_model - step));
  }
  Eigen::Matrix4d ecef_from_model = Eigen::Matrix4d::Identity();
  ecef_from_model.topLeftCorner<3, 3>() = axes;
  ecef_from_model.topRightCorner<3, 1>() = ecef_at(point_in_model) - axes * point_in_model;
  return ecef_from_model;
}

}  // namespace lutex
