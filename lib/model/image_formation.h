#pragma once

// The one place that owns lutex's image formation model (DESIGN.md, paper Eq. 3-4), per channel c:
//
//     I_c = alpha_c(x) * cos_theta * rho_c + beta_c(x)          (forward)
//     rho_c = (I_c - beta_c(x)) / (alpha_c(x) * cos_theta)      (restoration)
//
// x is the surface point in the camera frame, rho the albedo, alpha the signal factor and beta the
// backscatter stored in the FrustumLut. cos_theta is Lambertian shading (lib/model/shading.h, recorded in
// the LUT as FrustumLutGrid::shading): by default with the light approximated at the camera centre (the
// paper's choice), i.e. the cosine between the surface normal and the direction to the camera; or at one
// other point (a single flash); or weighted over a known light rig. A flash 0.1 m beside the camera and
// boards tilted by 11 degrees otherwise
// cost 5 % of albedo in restoration, twice the noise floor (simulated, calibrator_test). Unlike the paper, which divides the whole observation by cos_theta, only the
// signal is divided: backscatter is added in the water in front of the surface and does not depend on
// its orientation, so dividing it by cos_theta would be physically wrong. At grazing angles cos_theta is
// clamped to `min_cos_theta` (the restoration then has low confidence, see GrazingConfidence).

#include <algorithm>

#include <Eigen/Core>

namespace lutex {

struct ImageFormationOptions {
  // Smallest shading cosine used in restoration (about 84 degrees); below it the pixel is grazing.
  double min_cos_theta = 0.1;
};

// cos_theta with the light at `light_in_cam`: normal . (light - point) / |light - point|. Negative for
// back faces. (Shading, lib/model/shading.h, is what calibration and restoration call.)
double ShadingCosine(const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam,
                     const Eigen::Vector3d& light_in_cam = Eigen::Vector3d::Zero());

Eigen::Vector3d PredictIntensity(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                                 const Eigen::Vector3d& albedo);

// rho of one channel; cos_theta clamped at options.min_cos_theta.
template <typename Scalar>
Scalar RestoreChannel(Scalar alpha, Scalar beta, Scalar cos_theta, Scalar intensity,
                      const ImageFormationOptions& options = {}) {
  return (intensity - beta) / (alpha * std::max(cos_theta, static_cast<Scalar>(options.min_cos_theta)));
}

Eigen::Vector3d RestoreAlbedo(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                              const Eigen::Vector3d& intensity, const ImageFormationOptions& options = {});

// 1 for cos_theta >= 2 * min_cos_theta, falling linearly to 0 at min_cos_theta and below.
template <typename Scalar>
Scalar GrazingConfidence(Scalar cos_theta, const ImageFormationOptions& options = {}) {
  const Scalar min_cos_theta = static_cast<Scalar>(options.min_cos_theta);
  return std::clamp((cos_theta - min_cos_theta) / min_cos_theta, Scalar(0), Scalar(1));
}

}  // namespace lutex
