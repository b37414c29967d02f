#pragma once

// The one place that owns lutex's image formation model (DESIGN.md, paper Eq. 3-4), per channel c:
//
//     I_c = alpha_c(x) * cos_theta * rho_c + beta_c(x)          (forward)
//     rho_c = (I_c - beta_c(x)) / (alpha_c(x) * cos_theta)      (restoration)
//
// x is the surface point in the camera frame, rho the albedo, alpha the signal factor and beta the
// backscatter stored in the FrustumLut. cos_theta is Lambertian shading with the light approximated at one
// point: by default the camera centre (the paper's choice), i.e. the cosine between the surface normal and
// the direction from the point to the camera. With a known rig the point can move (e.g. onto a single
// flash; the LUT records it as FrustumLutGrid::shading_light_in_cam): a flash 0.1 m beside the camera and boards tilted by 11 degrees otherwise
// cost 5 % of albedo in restoration, twice the noise floor (simulated, calibrator_test). Unlike the paper, which divides the whole observation by cos_theta, only the
// signal is divided: backscatter is added in the water in front of the surface and does not depend on
// its orientation, so dividing it by cos_theta would be physically wrong. At grazing angles cos_theta is
// clamped to `min_cos_theta` (the restoration then has low confidence, see GrazingConfidence).

#include <Eigen/Core>

namespace lutex {

struct ImageFormationOptions {
  // Smallest shading cosine used in restoration (about 84 degrees); below it the pixel is grazing.
  double min_cos_theta = 0.1;
};

// cos_theta with the light at `light_in_cam`: normal . (light - point) / |light - point|. Negative for
// back faces.
double ShadingCosine(const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam,
                     const Eigen::Vector3d& light_in_cam = Eigen::Vector3d::Zero());

Eigen::Vector3d PredictIntensity(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                                 const Eigen::Vector3d& albedo);

Eigen::Vector3d RestoreAlbedo(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta, double cos_theta,
                              const Eigen::Vector3d& intensity, const ImageFormationOptions& options = {});

// 1 for cos_theta >= 2 * min_cos_theta, falling linearly to 0 at min_cos_theta and below.
double GrazingConfidence(double cos_theta, const ImageFormationOptions& options = {});

}  // namespace lutex
