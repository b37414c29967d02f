#pragma once

// A physically based prior under the free-form LUT: the water fitted to the calibration's own
// observations. The LUT's reference (the shape its smoothness keeps, the weights of its constraints, and
// what it falls back to where data are thin) used to be rendered for a named water the user picked; in a
// water other than the one named it pulled the solve the wrong way (turbid Blender boards with the clear
// preset: in-sample albedo p95 46 pp). Now the water is measured.
//
// The model, per channel c, with the rig the calibration shades with (or a point light at the camera):
//   alpha(x) = k_c * alpha_sim(x; attenuation cs_c),   beta(x) = s_c * beta_sim(x; attenuation cb_c)
// where alpha_sim, beta_sim are the simulator's TrueLut (lib/model/simulator.h) for a water of the given
// attenuation, with the start water's single-scattering albedo b / c and phase function. Four numbers
// per channel:
//   - cs, the effective attenuation of the signal. The simulator removes all scattered light from the
//     direct paths; real water returns the forward-scattered part, so cs lies between a + b (1 - g) and
//     a + b. It is fitted, not derived.
//   - cb, the attenuation that shapes backscatter over depth.
//   - k (light power times exposure) and s (scattering times exposure), linear given cs and cb.
// cs and cb are searched over a grid of attenuations (0 to 3 per metre) on a coarse LUT; for every pair
// (k, s) is the weighted least-squares solution (k, s >= 0) of
//   known colours:     k alpha_sim cos_theta rho + s beta_sim = I
//   correspondences:   alpha_2 cos_2 (I_1 - s beta_1) - alpha_1 cos_1 (I_2 - s beta_2) = 0  (k cancels)
//   pure water:        s beta_sim(ray, far) = I_pw   (a pure-water pixel is backscatter to infinity)
// each residual divided by (its intensity + the median intensity), so a dim far observation counts as
// much as a bright near one in relative terms (what restoration errors are made of), while one darker
// than the median (black squares, noise) counts in absolute terms. Without known colours k is set
// so the correspondences' surfaces average to the grey-world albedo.
//
// In air (a start water with no attenuation) only k is fitted, and with a guessed rig the position of its
// single light: a flash beside the lens, which shades tilted surfaces differently from a light at the
// camera. It is searched over +-0.3 m across the camera's x and y, each candidate shading the observations
// itself (cos_theta from their normals, lib/model/shading.h). In water the candidate rigs are compared on
// the observations as they were shaded (water_prior.cc says why).

#include <string>

#include <Eigen/Core>

#include "lib/calibration/observations.h"
#include "lib/geometry/camera.h"
#include "lib/lut/frustum_lut.h"
#include "lib/model/light_rig.h"
#include "lib/model/water.h"

namespace lutex {

struct WaterPriorOptions {
  // The water whose single-scattering albedo and phase function shape backscatter (a named preset).
  Water start;
  // Without known colours: the mean albedo of the correspondences' surfaces (calibrator.h).
  Eigen::Vector3d grey_world_albedo = Eigen::Vector3d::Zero();
  // The rig is a guess (a light at the camera, no beam profile given): also fit the beam, a cosine-power
  // profile cos(psi)^n along the camera axis, n from 0 (isotropic) to 8, one for all lights, and where the
  // lights are (in water a symmetric pair beside the camera, in air the single light's position).
  bool fit_beam = false;
  // Threads; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;
};

struct WaterPrior {
  // Fitted in air: no attenuation, no backscatter, only the light.
  bool in_air = false;
  // Per channel, per metre: signal attenuation cs and backscatter attenuation cb.
  Eigen::Vector3d signal_attenuation = Eigen::Vector3d::Zero();
  Eigen::Vector3d backscatter_attenuation = Eigen::Vector3d::Zero();
  // Per channel: k and s of the model above.
  Eigen::Vector3d signal_scale = Eigen::Vector3d::Zero();
  Eigen::Vector3d backscatter_scale = Eigen::Vector3d::Zero();
  // The rig the prior was rendered with: the given one, or with its fitted beam.
  LightRig rig;
  // Per channel: root-mean-square relative residual of the fit (residual / (intensity + floor)).
  Eigen::Vector3d relative_rms = Eigen::Vector3d::Zero();
  // The prior on the calibration grid, in the images' intensity units.
  FrustumLut lut;
  // Per node and channel (in beta; alpha is 0), the fraction of the open water's backscatter along the
  // node's ray that the model's backscatter reaches at the node's range (in [0, 1]).
  FrustumLut backscatter_reached;
};

// Fits the model above. `rig` is what shading assumes (lib/model/shading.h). Throws std::invalid_argument
// without known colours, correspondences or pure water, or without known colours and a grey-world albedo.
WaterPrior FitWaterPrior(const ObservationSet& observations, const LightRig& rig, const Camera& camera,
                         const FrustumLutGrid& grid, const WaterPriorOptions& options);

// The fitted attenuations (in water) and the rig's lights, one line for messages.
std::string DescribeWaterPrior(const WaterPrior& prior);

}  // namespace lutex
