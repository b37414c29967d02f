#include "lib/model/image_formation.h"

#include <algorithm>

namespace lutex {

double ShadingCosine(const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam,
                     const Eigen::Vector3d& light_in_cam) {
  return normal_in_cam.normalized().dot((light_in_cam - point_in_cam).normalized());
}

Eigen::Vector3d PredictIntensity(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                                 const Eigen::Vector3d& albedo) {
  return alpha.cwiseProduct(albedo) * std::max(cos_theta, 0.0) + beta;
}

Eigen::Vector3d RestoreAlbedo(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                              const Eigen::Vector3d& intensity, const ImageFormationOptions& options) {
  Eigen::Vector3d albedo;
  for (int c = 0; c < 3; ++c) albedo[c] = RestoreChannel(alpha[c], beta[c], cos_theta, intensity[c], options);
  return albedo;
}

}  // namespace lutex
