#pragma once

// Weights of the calibration's constraints (paper Sec. 2.4, "Weights and Accuracy"), derived from a
// reference LUT pre-rendered by the simulator for a single point light at the camera in the expected
// water, scaled to the images' intensity units.
//
// Smoothness: with grad the mean absolute difference between neighbouring nodes within slab N (or between
// slabs N and N+1) of the reference,
//   w_alpha(N) = scale * alpha_factor / grad_alpha(N),   w_beta(N) = scale / grad_beta(N)
// with the paper's scale 0.01 and alpha_factor 0.7 (the average scene intensity, which brings alpha and
// beta to one scale). Where the reference is flat (beta in air) the gradient is floored at 1e-6 of the
// quantity's largest value. With inverse-square alpha interpolation, alpha between slabs is compared as
// alpha * z^2 (the interpolated quantity), as the calibration's smoothness residuals do.
//
// Known colour, per channel: w = 1 / d_v * s_N * abar_N / max(alpha_ref(x) cos_theta, 0.05 abar_N) / (e^(0.5 d))^2
// with d the distance from the camera and
//   s_N = mean_N / (n_shot + n_const), the paper's signal-to-noise at slab N's mean intensity mean_N,
//   n_shot = 0.01 sqrt(mean_N), n_const = mean_N / (snr_0 * mean_0,green), snr_0 = 10 (20 dB),
//   mean_N = 0.7 mean(alpha_N) + mean(beta_N), abar_N = mean(alpha_N), both over slab N of the reference,
//   alpha_ref(x) the reference's alpha at the observation.
// The weighted residual w (alpha cos_theta rho + beta - I) is then the observation's albedo error (its
// residual over alpha cos_theta) in units of the slab's noise. The paper weighs by the observation's own
// snr = I / (n_shot + n_const) instead, which grows with the observed intensity: the dim observations (the
// image's edges outside the spots' cones, red at range, turbid water) counted least exactly where an
// intensity error is the largest albedo error, and the LUT there followed the reference, not the data.
// Measured (README, 'Weights in albedo units'): simulated dives over three waters and two rigs no worse and
// up to 3 pp better (coastal), Blender turbid boards restored with their own LUT 5.8 -> 4.4 pp. Dropping the
// distance term as well helped the Blender sets more but made the simulated dives it was tried on worse.
// The floor 0.05 abar_N only guards against a reference alpha of 0 (results did not change between 0.02
// and 0.2). The paper's d_v, the distance from the voxel centre, is unbounded at a node; lutex measures it
// in node spacings to the nearest node and floors it at 0.25.
//
// Correspondence, per channel (paper): w_c = w_1 w_2 / sqrt(w_1^2 + w_2^2) from the known-colour weights
// of its two views.

#include <vector>

#include <Eigen/Core>

#include "lib/calibration/observations.h"
#include "lib/lut/frustum_lut.h"

namespace lutex {

struct SmoothnessWeights {
  std::vector<Eigen::Vector3d> alpha_within, beta_within;    // one per slab
  std::vector<Eigen::Vector3d> alpha_between, beta_between;  // one per pair of neighbouring slabs
};

SmoothnessWeights ComputeSmoothnessWeights(const FrustumLut& reference, double scale = 0.01, double alpha_factor = 0.7);

// The known-colour weight above. The slab means of the reference are computed once, at construction, not
// per observation. Keeps a reference to `reference`, which must outlive it.
class KnownColorWeighting {
 public:
  explicit KnownColorWeighting(const FrustumLut& reference);
  Eigen::Vector3d operator()(const KnownColorObservation& observation) const;
  Eigen::Vector3d operator()(const CorrespondenceObservation& observation) const;

 private:
  Eigen::Vector3d ViewWeight(const Eigen::Vector2d& pixel, const Eigen::Vector3d& point_in_cam, double cos_theta) const;

  const FrustumLut& reference_;
  std::vector<Eigen::Vector3d> slab_means_;        // mean_N per slab
  std::vector<Eigen::Vector3d> slab_alpha_means_;  // abar_N per slab
};

}  // namespace lutex
