#pragma once

// Fitting a FrustumLut to observations (paper Sec. 2.2-2.4): known colours, correspondences between views
// of the same surface, smoothness between the six neighbours of every node, pure-water upper bounds on
// beta (and lower ones from the water prior, below), and positivity of alpha and beta. Solved by
// Ceres (Levenberg-Marquardt, sparse Cholesky) for the three channels independently and in parallel,
// coarse to fine: each level's nx x ny cells are solved starting from the previous level resampled
// (corner-aligned grids nest exactly, see frustum_lut.h). In air, beta is held at 0.
//
// Smoothness departs from the paper's plain differences alpha_a - alpha_b: it keeps the shape of the
// pre-rendered reference LUT (alpha_a / ref_a = alpha_b / ref_b), because a plain difference prefers a
// flat LUT and pulled the dim image corners and far slabs towards the bright centre (on simulated boards:
// held-out restoration error 2.9 % -> 1.9 % median, 12 % -> 5.8 % p90). The weights are the paper's.
//
// Smoothness is weighed against each channel's data in that channel's units: the paper's data residuals
// are in intensity units (and its SNR weights grow with intensity) while its smoothness residuals are
// unitless, so a dark channel (blue when a board's blue albedo is 0.013) was regularised far harder than
// the bright ones and its alpha pulled off the data (Blender boards: blue alpha 16 % low at 2 m, blue
// patches 10-14 pp off). Every smoothness weight of channel c is therefore multiplied by I_c / max_c I_c,
// I_c the channel's mean observed intensity (known colours, else correspondence views): the brightest
// channel keeps the paper's weights. (Scaling by I_c itself fixed the blue too, but made a dim dive's
// smoothness 10x weaker than the paper's everywhere: a chessboard-only LUT then extrapolated worse,
// 4.1 -> 7.2 pp.)
//
// Pure water departs from the paper's one-sided bound beta <= I_pw when the water prior is given: a
// pure-water pixel sees the backscatter along its ray to infinity, and the prior says what fraction f of
// it backscatter reaches at each range (in turbid water nearly all of it beyond a metre or two), so
// beta >= f I_pw as well, weighted lower. Without it, where the known colours cannot tell alpha from beta
// (far, dim, turbid: two board albedos whose difference is a tenth of the backscatter), the level of beta
// was free, smoothness kept only its shape, and it settled low: on the turbid Blender boards at 55 % of
// the pure-water intensity at 2 m, which left the restored seafloor's image edges 17-21 pp too bright in
// red.
//
// Correspondences alone are satisfied by alpha = 0 and fix alpha only up to a factor per channel. The
// paper normalises sum(alpha) = 1; that one residual would touch every node and make the sparse normal
// equations dense, so lutex fixes the same gauge by holding alpha of one node (the one the correspondences
// touch most) at its initial value, then sets the absolute scale per channel after the solve: from the
// known colours when there are any (they then fix the scale themselves and no node is held), else from
// `grey_world_albedo`, the mean albedo the user asserts for the surveyed surfaces (a grey-world
// assumption, only on explicit request). The correspondence residual is divided by the reference's
// alpha cos_theta at the two views, so it is in intensity units like the known-colour residual.

#include <utility>

#include <Eigen/Core>
#include <vector>

#include "lib/calibration/observations.h"
#include "lib/calibration/residual_histogram.h"
#include "lib/lut/frustum_lut.h"

namespace lutex {

struct CalibrationOptions {
  // The finest grid (its nx, ny must equal the last level's); nz, depth range, spacing and image size
  // are shared by all levels.
  FrustumLutGrid grid;
  // Cells across and down per level, coarse to fine (paper: 4x3 -> 20x15 -> 40x30).
  std::vector<std::pair<int, int>> levels = {{4, 3}, {20, 15}, {40, 30}};
  // In air: no backscatter, beta fixed at 0 (one known colour is then enough).
  bool in_air = false;
  // Smoothness weights relative to observations (paper: 0.01) and alpha's factor (paper: 0.7).
  double smoothness_scale = 0.01;
  double alpha_smoothness_factor = 0.7;
  // Weight of a pure-water bound violation, per unit of excess beta.
  double pure_water_weight = 100.0;
  // Weight, per unit of beta, of falling short of the fraction of a pure-water pixel's intensity that the
  // water prior says backscatter reaches at a slab's range (Calibrate's `backscatter_reached`). Lower than
  // the bound's: the bound is physics, the fraction is a fitted model's.
  double pure_water_reached_weight = 30.0;
  // Factor on the paper's correspondence weights.
  double correspondence_weight = 1.0;
  // Without known colours: the mean albedo, per channel, of the correspondences' surfaces that sets the
  // absolute scale (grey world). Required (> 0) when there are no known colours; ignored otherwise.
  Eigen::Vector3d grey_world_albedo = Eigen::Vector3d::Zero();
  // Levenberg-Marquardt iterations per level and channel, and the relative cost change that ends them.
  // The problem is linear but for its bounds (alpha, beta >= 0, one-sided pure water) and each level
  // starts from the last one's solution; beyond ~10 iterations LM mostly crawls along active bounds. On
  // the Blender boards (40 x 30 x 10, 100 k observations, rig shading) 10 iterations and 1e-4 gave the
  // same ColorChecker errors as 100 and Ceres' 1e-6 (median 0.50 vs 0.51, worst 6.06 vs 6.12) in 24 s
  // instead of 60 s. Experiments that compare what constraints determine should run to convergence.
  int max_iterations = 10;
  double function_tolerance = 1e-4;
  // Threads over channels; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;

  // Throws std::invalid_argument on nonsense.
  void Check() const;
};

struct CalibrationLevelSummary {
  int nx = 0, ny = 0;
  int iterations[3] = {0, 0, 0};
  double final_cost[3] = {0, 0, 0};
};

struct CalibrationSummary {
  std::vector<CalibrationLevelSummary> levels;
  std::size_t num_known_color = 0;
  std::size_t num_pure_water = 0;
  // Root-mean-square of the unweighted known-colour residuals (predicted - observed), per channel.
  Eigen::Vector3d known_color_rms = Eigen::Vector3d::Zero();
  std::size_t num_correspondences = 0;
  // Root-mean-square difference of the albedo the two views of a correspondence restore to, per channel.
  Eigen::Vector3d correspondence_albedo_rms = Eigen::Vector3d::Zero();
  // Largest pure-water bound violation (beta - I_pw) over all bounds, per channel; 0 when none.
  Eigen::Vector3d pure_water_max_violation = Eigen::Vector3d::Zero();
  // Fraction of the finest LUT's nodes constrained by data (see coverage).
  double covered_fraction = 0.0;
  double seconds = 0.0;
  // Distributions after the solve: known-colour residuals (predicted - observed intensity), albedo
  // differences between the two views of a correspondence, and pure-water excess (beta - I_pw at every
  // slab along the ray; negative = bound kept).
  ResidualHistogram known_color_residuals{0.05, 40};
  ResidualHistogram correspondence_albedo_differences{0.2, 40};
  ResidualHistogram pure_water_excess{0.01, 40};
};

struct CalibrationResult {
  FrustumLut lut;
  // Per node, in alpha (all three channels equal): how well data constrained it, in [0, 1] (1 when at
  // least 4 known-colour observations or correspondence views with non-negligible weight touch the
  // node). Restoration uses it for confidence.
  FrustumLut coverage;
  CalibrationSummary summary;
};

// `reference` is the weighting LUT on options.grid (a point light at the camera in the expected water,
// any intensity scale: it is rescaled to the data). `backscatter_reached`, when given (on options.grid,
// the water prior's WaterPrior::backscatter_reached), also bounds beta from below along pure-water rays:
// without it, nothing but the known colours sets the level of beta, and where they cannot tell alpha from
// beta (far, dim, turbid) smoothness keeps only beta's shape. Needs known colours or correspondences (then
// with options.grey_world_albedo).
CalibrationResult Calibrate(const ObservationSet& observations, const FrustumLut& reference,
                            const CalibrationOptions& options, const FrustumLut* backscatter_reached = nullptr);

}  // namespace lutex
