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
  const double shading = std::max(cos_theta, options.min_cos_theta);
  return (intensity - beta).cwiseQuotient(alpha * shading);
}

double GrazingConfidence(double cos_theta, const ImageFormationOptions& options) {
  return std::clamp((cos_theta - options.min_cos_theta) / options.min_cos_theta, 0.0, 1.0);
}

}  // namespace lutex
