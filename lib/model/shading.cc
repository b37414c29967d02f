#include "lib/model/shading.h"

#include <algorithm>

#include "lib/model/image_formation.h"

namespace lutex {

double Shading::Cosine(const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam) const {
  if (rig.lights.empty()) return ShadingCosine(point_in_cam, normal_in_cam, light_in_cam);
  const Eigen::Vector3d normal = normal_in_cam.normalized();
  double weighted_cosine = 0.0, irradiance = 0.0;
  for (const Light& light : rig.lights) {
    const Eigen::Vector3d to_light = light.position_in_cam - point_in_cam;
    const double squared_distance = to_light.squaredNorm();
    if (!(squared_distance > 0.0)) continue;
    const Eigen::Vector3d omega = to_light / std::sqrt(squared_distance);
    const double cos_psi = -omega.dot(light.direction_in_cam);
    const double here = light.intensity.mean() * light.Profile(cos_psi) / squared_distance;
    weighted_cosine += here * std::max(normal.dot(omega), 0.0);
    irradiance += here;
  }
  if (!(irradiance > 0.0)) return ShadingCosine(point_in_cam, normal_in_cam);
  return weighted_cosine / irradiance;
}

bool Shading::operator==(const Shading& other) const {
  if (light_in_cam != other.light_in_cam || rig.lights.size() != other.rig.lights.size()) return false;
  for (std::size_t l = 0; l < rig.lights.size(); ++l) {
    const Light &a = rig.lights[l], &b = other.rig.lights[l];
    if (a.position_in_cam != b.position_in_cam || a.direction_in_cam != b.direction_in_cam || a.intensity != b.intensity ||
        a.profile != b.profile || a.exponent != b.exponent || a.sigma_rad != b.sigma_rad ||
        a.spot_size_rad != b.spot_size_rad || a.spot_blend != b.spot_blend) {
      return false;
    }
  }
  return true;
}

}  // namespace lutex
