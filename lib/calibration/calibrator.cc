#include "lib/calibration/calibrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <ceres/ceres.h>

#include "lib/calibration/calibration_weights.h"
#include "lib/calibration/cost_functions.h"
#include "lib/model/image_formation.h"
#include "lib/util/parallel_for.h"
#include "lib/util/median.h"

namespace lutex {
namespace {

using NodeValues = std::vector<std::array<double, 2>>;  // (alpha, beta) per node, one channel

FrustumLutGrid LevelGrid(const FrustumLutGrid& finest, const std::pair<int, int>& level) {
  FrustumLutGrid grid = finest;
  grid.nx = level.first;
  grid.ny = level.second;
  return grid;
}

// The reference LUT rescaled so its alpha matches the data's typical I / (cos_theta rho): from the known
// colours, or without them from the correspondences' views with the grey-world albedo.
FrustumLut ScaledReference(const FrustumLut& reference, const ObservationSet& observations,
                           const CalibrationOptions& options) {
  std::vector<double> data_ratio, reference_ratio;
  const auto add = [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point_in_cam, double intensity,
                       double shading_albedo) {
    if (shading_albedo <= 0.05) return;
    data_ratio.push_back(intensity / shading_albedo);
    reference_ratio.push_back(reference.Lookup(pixel.x(), pixel.y(), point_in_cam.z()).alpha.y());
  };
  for (const KnownColorObservation& observation : observations.known_colors) {
    add(observation.pixel, observation.point_in_cam, observation.intensity.y(),
        observation.cos_theta * observation.albedo.y());
  }
  if (observations.known_colors.empty()) {
    for (const CorrespondenceObservation& observation : observations.correspondences) {
      for (const SurfaceView* view : {&observation.first, &observation.second}) {
        add(view->pixel, view->point_in_cam, view->intensity.y(), view->cos_theta * options.grey_world_albedo.y());
      }
    }
  }
  const double reference_median = MedianInPlace(reference_ratio);
  const double scale = reference_median > 0 ? MedianInPlace(data_ratio) / reference_median : 1.0;
  FrustumLut scaled = reference;
  for (int n = 0; n < scaled.grid().NumNodes(); ++n) {
    scaled.node(n).alpha *= scale;
    scaled.node(n).beta *= scale;
  }
  return scaled;
}

// The mean observed intensity per channel of the observations that carry data: the known colours, or
// without them the correspondences' views. Floored so a black channel cannot switch smoothness off.
Eigen::Vector3d MeanDataIntensity(const ObservationSet& observations) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double count = 0.0;
  for (const KnownColorObservation& observation : observations.known_colors) {
    sum += observation.intensity.cwiseMax(0.0);
    ++count;
  }
  if (observations.known_colors.empty()) {
    for (const CorrespondenceObservation& observation : observations.correspondences) {
      sum += observation.first.intensity.cwiseMax(0.0) + observation.second.intensity.cwiseMax(0.0);
      count += 2.0;
    }
  }
  return (count > 0.0 ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Ones()).cwiseMax(1e-4);
}

// Smoothness weighed against each channel's data (calibrator.h): every weight of channel c times
// `relative_intensity`[c].
void ScaleToDataIntensity(const Eigen::Vector3d& relative_intensity, SmoothnessWeights* weights) {
  for (auto* per_slab : {&weights->alpha_within, &weights->beta_within, &weights->alpha_between, &weights->beta_between}) {
    for (Eigen::Vector3d& weight : *per_slab) weight = weight.cwiseProduct(relative_intensity);
  }
}

// The albedo a view restores to with `lut`, per channel (not finite where alpha is 0).
Eigen::Vector3d ViewAlbedo(const FrustumLut& lut, const SurfaceView& view) {
  const LutNode node = lut.Lookup(view.pixel.x(), view.pixel.y(), view.point_in_cam.z());
  return RestoreAlbedo(node.alpha, node.beta, view.cos_theta, view.intensity);
}

// The node the correspondences touch most (interpolation weight summed), which holds the gauge when no
// known colour fixes alpha's scale; -1 when there are no correspondences.
int GaugeNode(const FrustumLut& level_lut, const ObservationSet& observations) {
  std::vector<double> touch(static_cast<std::size_t>(level_lut.grid().NumNodes()), 0.0);
  for (const CorrespondenceObservation& observation : observations.correspondences) {
    for (const SurfaceView* view : {&observation.first, &observation.second}) {
      const NodeWeights weights = level_lut.Weights(view->pixel.x(), view->pixel.y(), view->point_in_cam.z());
      for (int n = 0; n < weights.count; ++n) touch[static_cast<std::size_t>(weights.node[n])] += weights.weight[n];
    }
  }
  if (observations.correspondences.empty()) return -1;
  return static_cast<int>(std::max_element(touch.begin(), touch.end()) - touch.begin());
}

struct ChannelProblemInput {
  const ObservationSet& observations;
  const std::vector<Eigen::Vector3d>& known_color_weights;
  const std::vector<Eigen::Vector3d>& correspondence_weights;
  int gauge_node;  // node whose alpha is held (no known colours), or -1
  const FrustumLut& level_lut;  // grid of this level (values unused)
  const FrustumLut& level_reference;  // the weighting LUT on this level: the shape smoothness keeps
  const FrustumLut* level_backscatter_reached;  // per node, the fraction of open water's backscatter, or null
  const SmoothnessWeights& smoothness;
  const CalibrationOptions& options;
};

// Solves one channel on one level, starting from `values`.
// Known colours: alpha cos_theta albedo + beta = the observed intensity, at the observation's nodes.
void AddKnownColorResiduals(const ChannelProblemInput& input, int channel, NodeValues* values, ceres::Problem* problem) {
  const auto block = [values](int node) { return (*values)[static_cast<std::size_t>(node)].data(); };
  for (std::size_t o = 0; o < input.observations.known_colors.size(); ++o) {
    const KnownColorObservation& observation = input.observations.known_colors[o];
    const double weight = input.known_color_weights[o][channel];
    if (!(weight > 0.0)) continue;
    const NodeWeights weights =
        input.level_lut.Weights(observation.pixel.x(), observation.pixel.y(), observation.point_in_cam.z());
    std::vector<double> alpha_weights(weights.alpha_weight.begin(), weights.alpha_weight.begin() + weights.count);
    std::vector<double> beta_weights(weights.weight.begin(), weights.weight.begin() + weights.count);
    std::vector<double*> blocks;
    for (int n = 0; n < weights.count; ++n) blocks.push_back(block(weights.node[n]));
    problem->AddResidualBlock(KnownColorResidual::Create(std::move(alpha_weights), std::move(beta_weights),
                                                        observation.cos_theta * observation.albedo[channel],
                                                        observation.intensity[channel], weight),
                             nullptr, blocks);
  }
}

// Correspondences: two views of one surface point restore to the same albedo.
void AddCorrespondenceResiduals(const ChannelProblemInput& input, int channel, NodeValues* values, ceres::Problem* problem) {
  const auto block = [values](int node) { return (*values)[static_cast<std::size_t>(node)].data(); };
  for (std::size_t o = 0; o < input.observations.correspondences.size(); ++o) {
    const CorrespondenceObservation& observation = input.observations.correspondences[o];
    const double weight = input.correspondence_weights[o][channel];
    if (!(weight > 0.0)) continue;
    // Union of the two views' nodes, with each view's interpolation weights.
    std::vector<int> nodes;
    std::vector<std::array<double, 4>> coefficients;
    const auto add_view = [&](const SurfaceView& view, int offset) {
      const NodeWeights weights = input.level_lut.Weights(view.pixel.x(), view.pixel.y(), view.point_in_cam.z());
      for (int n = 0; n < weights.count; ++n) {
        const auto found = std::find(nodes.begin(), nodes.end(), weights.node[n]);
        const std::size_t slot = static_cast<std::size_t>(found - nodes.begin());
        if (found == nodes.end()) {
          nodes.push_back(weights.node[n]);
          coefficients.push_back({0.0, 0.0, 0.0, 0.0});
        }
        coefficients[slot][static_cast<std::size_t>(offset)] += weights.alpha_weight[n];
        coefficients[slot][static_cast<std::size_t>(offset) + 1] += weights.weight[n];
      }
    };
    add_view(observation.first, 0);
    add_view(observation.second, 2);
    // In intensity units: divided by the reference's alpha cos_theta, the residual is about the
    // difference of the two views' observations once restored to the same albedo.
    const auto reference_signal = [&](const SurfaceView& view) {
      return input.level_reference.Lookup(view.pixel.x(), view.pixel.y(), view.point_in_cam.z()).alpha[channel] *
             view.cos_theta;
    };
    const double scale = 0.5 * (reference_signal(observation.first) + reference_signal(observation.second));
    if (!(scale > 0.0)) continue;
    std::vector<double*> blocks;
    for (int node : nodes) blocks.push_back(block(node));
    problem->AddResidualBlock(
        CorrespondenceResidual::Create(std::move(coefficients), observation.first.cos_theta,
                                       observation.first.intensity[channel], observation.second.cos_theta,
                                       observation.second.intensity[channel], weight / scale),
        nullptr, blocks);
  }
}

// Pure water: beta at every slab along a pure-water pixel's ray stays below what the pixel saw and, with
// the water prior's fractions, above the fraction of it backscatter reaches at the slab (not in air).
void AddPureWaterResiduals(const ChannelProblemInput& input, int channel, NodeValues* values, ceres::Problem* problem) {
  const auto block = [values](int node) { return (*values)[static_cast<std::size_t>(node)].data(); };
  const FrustumLutGrid& grid = input.level_lut.grid();
  for (const PureWaterObservation& observation : input.observations.pure_water) {
    for (int k = 0; k < grid.nz; ++k) {
      const NodeWeights weights = input.level_lut.Weights(observation.pixel.x(), observation.pixel.y(), grid.SlabDepth(k));
      std::vector<double> beta_weights(weights.weight.begin(), weights.weight.begin() + weights.count);
      std::vector<double*> blocks;
      for (int n = 0; n < weights.count; ++n) blocks.push_back(block(weights.node[n]));
      const double reached =
          input.level_backscatter_reached == nullptr
              ? 0.0
              : input.level_backscatter_reached->Lookup(observation.pixel.x(), observation.pixel.y(), grid.SlabDepth(k))
                    .beta[channel];
      problem->AddResidualBlock(
          PureWaterBoundResidual::Create(std::move(beta_weights), observation.intensity[channel],
                                         input.options.pure_water_weight * observation.weight, reached,
                                         input.options.pure_water_reached_weight * observation.weight),
          nullptr, blocks);
    }
  }
}

// Smoothness between neighbouring nodes, within and between slabs, following the reference's shape.
void AddSmoothnessResiduals(const ChannelProblemInput& input, int channel, NodeValues* values, ceres::Problem* problem) {
  const auto block = [values](int node) { return (*values)[static_cast<std::size_t>(node)].data(); };
  const FrustumLutGrid& grid = input.level_lut.grid();
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        const int here = grid.NodeIndex(i, j, k);
        // Smoothness keeps the shape of the reference (a point light at the camera in the expected water):
        // x_here / ref_here = x_there / ref_there, written in x_here's units. A plain difference would
        // prefer a flat LUT and pull the dim image corners and far slabs towards the bright centre.
        const auto shape_scale = [&](int there, int component) {
          const LutNode& a = input.level_reference.node(here);
          const LutNode& b = input.level_reference.node(there);
          const double ref_a = component == 0 ? a.alpha[channel] : a.beta[channel];
          const double ref_b = component == 0 ? b.alpha[channel] : b.beta[channel];
          return ref_a > 0.0 && ref_b > 0.0 ? ref_a / ref_b : 1.0;
        };
        const auto add = [&](int there, double alpha_weight, double beta_weight) {
          problem->AddResidualBlock(SmoothnessResidual::Create(0, alpha_weight, 1.0, shape_scale(there, 0)), nullptr,
                                   block(here), block(there));
          if (!input.options.in_air) {
            problem->AddResidualBlock(SmoothnessResidual::Create(1, beta_weight, 1.0, shape_scale(there, 1)), nullptr,
                                     block(here), block(there));
          }
        };
        if (i + 1 < grid.NodesX()) {
          add(grid.NodeIndex(i + 1, j, k), input.smoothness.alpha_within[k][channel], input.smoothness.beta_within[k][channel]);
        }
        if (j + 1 < grid.NodesY()) {
          add(grid.NodeIndex(i, j + 1, k), input.smoothness.alpha_within[k][channel], input.smoothness.beta_within[k][channel]);
        }
        if (k + 1 < grid.nz) {
          add(grid.NodeIndex(i, j, k + 1), input.smoothness.alpha_between[k][channel],
              input.smoothness.beta_between[k][channel]);
        }
      }
    }
  }
}

// alpha, beta >= 0; in air beta is fixed at 0; the gauge node fixes the scale the data leave free.
void BoundNodesAndFixGauge(const ChannelProblemInput& input, NodeValues* values, ceres::Problem* problem) {
  const auto block = [values](int node) { return (*values)[static_cast<std::size_t>(node)].data(); };
  const FrustumLutGrid& grid = input.level_lut.grid();
  for (int n = 0; n < grid.NumNodes(); ++n) {
    if (!problem->HasParameterBlock(block(n))) continue;
    problem->SetParameterLowerBound(block(n), 0, 0.0);
    if (input.options.in_air) {
      (*values)[static_cast<std::size_t>(n)][1] = 0.0;
      if (n == input.gauge_node) {
        problem->SetParameterBlockConstant(block(n));
      } else {
        problem->SetManifold(block(n), new ceres::SubsetManifold(2, {1}));
      }
    } else {
      problem->SetParameterLowerBound(block(n), 1, 0.0);
      if (n == input.gauge_node) problem->SetManifold(block(n), new ceres::SubsetManifold(2, {0}));
    }
  }
}

// Sparse Cholesky where the factor is small, conjugate gradients on the normal equations where it is not.
ceres::Solver::Options ChannelSolverOptions(const ChannelProblemInput& input) {
  const FrustumLutGrid& grid = input.level_lut.grid();
  ceres::Solver::Options solver_options;
  // Correspondences link nodes far apart in the frustum, and on a large level a sparse Cholesky factor of
  // such a problem fills in (measured on the Blender seafloor's 41 x 31 x 10 nodes: 8x slower); conjugate
  // gradients on the normal equations need no factor. On small levels the exact factor is cheap and its
  // steps converge better (simulated in-air survey, 9 x 7 x 3 nodes: 1.1 % vs 1.8 % median error, 4x
  // faster), so CGNR is used only where the factor would be large.
  constexpr int kLargestFactoredLevel = 2000;  // nodes
  const bool large = !input.observations.correspondences.empty() && grid.NumNodes() > kLargestFactoredLevel;
  solver_options.linear_solver_type = large ? ceres::CGNR : ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = input.options.max_iterations;
  solver_options.function_tolerance = input.options.function_tolerance;
  solver_options.num_threads = 1;  // parallel over channels instead
  solver_options.logging_type = ceres::SILENT;
  return solver_options;
}

ceres::Solver::Summary SolveChannel(const ChannelProblemInput& input, int channel, NodeValues* values) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  AddKnownColorResiduals(input, channel, values, &problem);
  AddCorrespondenceResiduals(input, channel, values, &problem);
  if (!input.options.in_air) AddPureWaterResiduals(input, channel, values, &problem);
  AddSmoothnessResiduals(input, channel, values, &problem);
  BoundNodesAndFixGauge(input, values, &problem);
  ceres::Solver::Summary summary;
  ceres::Solve(ChannelSolverOptions(input), &problem, &summary);
  return summary;
}

}  // namespace

void CalibrationOptions::Check() const {
  grid.Check();
  if (levels.empty()) throw std::invalid_argument("calibration needs at least one level");
  if (levels.back().first != grid.nx || levels.back().second != grid.ny) {
    throw std::invalid_argument("the last calibration level must be the grid's nx x ny");
  }
  for (const auto& level : levels) {
    if (level.first < 1 || level.second < 1) throw std::invalid_argument("calibration levels need nx, ny >= 1");
  }
  if (!(smoothness_scale >= 0.0) || !(alpha_smoothness_factor > 0.0) || !(pure_water_weight >= 0.0) ||
      !(pure_water_reached_weight >= 0.0)) {
    throw std::invalid_argument("calibration weights must not be negative");
  }
  if (max_iterations < 1) throw std::invalid_argument("max_iterations must be at least 1");
  if (!(function_tolerance > 0.0)) throw std::invalid_argument("function_tolerance must be positive");
}

CalibrationResult Calibrate(const ObservationSet& observations, const FrustumLut& reference,
                            const CalibrationOptions& options, const FrustumLut* backscatter_reached) {
  options.Check();
  if (!(reference.grid() == options.grid)) throw std::invalid_argument("the reference LUT must be on the calibration grid");
  if (backscatter_reached != nullptr && !(backscatter_reached->grid() == options.grid)) {
    throw std::invalid_argument("the backscatter fractions must be on the calibration grid");
  }
  const bool self_calibrated = observations.known_colors.empty();
  if (self_calibrated && observations.correspondences.empty()) {
    throw std::invalid_argument("calibration needs known-colour observations or correspondences");
  }
  if (self_calibrated && !(options.grey_world_albedo.minCoeff() > 0.0)) {
    throw std::invalid_argument(
        "without known colours, correspondences fix alpha only up to a factor per channel: give a known colour "
        "or a grey-world albedo");
  }
  const auto start = std::chrono::steady_clock::now();
  const FrustumLut scaled_reference = ScaledReference(reference, observations, options);
  const KnownColorWeighting weighting(scaled_reference);
  std::vector<Eigen::Vector3d> known_color_weights, correspondence_weights;
  known_color_weights.reserve(observations.known_colors.size());
  for (const KnownColorObservation& observation : observations.known_colors) {
    known_color_weights.push_back(weighting(observation).cwiseProduct(observation.weight));
  }
  correspondence_weights.reserve(observations.correspondences.size());
  for (const CorrespondenceObservation& observation : observations.correspondences) {
    correspondence_weights.push_back(options.correspondence_weight * weighting(observation).cwiseProduct(observation.weight));
  }

  const Eigen::Vector3d data_intensity = MeanDataIntensity(observations);

  CalibrationResult result;
  result.summary.num_known_color = observations.known_colors.size();
  result.summary.num_pure_water = observations.pure_water.size();
  result.summary.num_correspondences = observations.correspondences.size();
  FrustumLut current;
  for (std::size_t l = 0; l < options.levels.size(); ++l) {
    const FrustumLutGrid grid = LevelGrid(options.grid, options.levels[l]);
    FrustumLut level_lut = l == 0 ? scaled_reference.Resampled(grid) : current.Resampled(grid);
    if (options.in_air) {
      for (int n = 0; n < grid.NumNodes(); ++n) level_lut.node(n).beta.setZero();
    }
    const FrustumLut level_reference = scaled_reference.Resampled(grid);
    const std::optional<FrustumLut> level_reached =
        backscatter_reached == nullptr ? std::nullopt : std::optional<FrustumLut>(backscatter_reached->Resampled(grid));
    SmoothnessWeights smoothness =
        ComputeSmoothnessWeights(level_reference, options.smoothness_scale, options.alpha_smoothness_factor);
    ScaleToDataIntensity(data_intensity / data_intensity.maxCoeff(), &smoothness);
    CalibrationLevelSummary level_summary;
    level_summary.nx = grid.nx;
    level_summary.ny = grid.ny;
    const int gauge_node = self_calibrated ? GaugeNode(level_lut, observations) : -1;
    const ChannelProblemInput input{observations, known_color_weights, correspondence_weights, gauge_node,
                                    level_lut, level_reference, level_reached ? &*level_reached : nullptr,
                                    smoothness, options};
    ParallelFor(3, options.num_threads, [&](std::size_t channel) {
      const int c = static_cast<int>(channel);
      NodeValues values(static_cast<std::size_t>(grid.NumNodes()));
      for (int n = 0; n < grid.NumNodes(); ++n) values[static_cast<std::size_t>(n)] = {level_lut.node(n).alpha[c], level_lut.node(n).beta[c]};
      const ceres::Solver::Summary summary = SolveChannel(input, c, &values);
      level_summary.iterations[c] = static_cast<int>(summary.iterations.size());
      level_summary.final_cost[c] = summary.final_cost;
      for (int n = 0; n < grid.NumNodes(); ++n) {
        // Each channel writes only its own component: no race between channels.
        level_lut.node(n).alpha[c] = values[static_cast<std::size_t>(n)][0];
        level_lut.node(n).beta[c] = values[static_cast<std::size_t>(n)][1];
      }
    });
    result.summary.levels.push_back(level_summary);
    current = level_lut;
  }
  result.lut = current;
  if (self_calibrated) {
    // The absolute scale per channel: the correspondences' surfaces average to the grey-world albedo.
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), count = Eigen::Vector3d::Zero();
    for (const CorrespondenceObservation& observation : observations.correspondences) {
      for (const SurfaceView* view : {&observation.first, &observation.second}) {
        const Eigen::Vector3d albedo = ViewAlbedo(result.lut, *view);
        for (int c = 0; c < 3; ++c) {
          if (!std::isfinite(albedo[c])) continue;
          sum[c] += albedo[c];
          count[c] += 1.0;
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      if (!(count[c] > 0.0) || !(sum[c] > 0.0)) {
        throw std::runtime_error("correspondences restore to no positive albedo; cannot set the grey-world scale");
      }
      const double factor = sum[c] / count[c] / options.grey_world_albedo[c];
      for (int n = 0; n < options.grid.NumNodes(); ++n) result.lut.node(n).alpha[c] *= factor;
    }
  }

  // Coverage and residual summary on the finest level.
  result.coverage = FrustumLut(options.grid);
  std::vector<int> touches(static_cast<std::size_t>(options.grid.NumNodes()), 0);
  Eigen::Vector3d squared = Eigen::Vector3d::Zero();
  for (std::size_t o = 0; o < observations.known_colors.size(); ++o) {
    const KnownColorObservation& observation = observations.known_colors[o];
    const NodeWeights weights = result.lut.Weights(observation.pixel.x(), observation.pixel.y(), observation.point_in_cam.z());
    for (int n = 0; n < weights.count; ++n) {
      if (weights.weight[n] > 0.1 && known_color_weights[o].minCoeff() > 0.0) ++touches[static_cast<std::size_t>(weights.node[n])];
    }
    const LutNode value = result.lut.Lookup(observation.pixel.x(), observation.pixel.y(), observation.point_in_cam.z());
    const Eigen::Vector3d predicted =
        value.alpha.cwiseProduct(observation.albedo) * observation.cos_theta + value.beta;
    squared += (predicted - observation.intensity).cwiseAbs2();
    result.summary.known_color_residuals.Add(predicted - observation.intensity);
  }
  if (!observations.known_colors.empty()) {
    result.summary.known_color_rms = (squared / static_cast<double>(observations.known_colors.size())).cwiseSqrt();
  }
  Eigen::Vector3d albedo_squared = Eigen::Vector3d::Zero(), albedo_count = Eigen::Vector3d::Zero();
  for (std::size_t o = 0; o < observations.correspondences.size(); ++o) {
    const CorrespondenceObservation& observation = observations.correspondences[o];
    for (const SurfaceView* view : {&observation.first, &observation.second}) {
      const NodeWeights weights = result.lut.Weights(view->pixel.x(), view->pixel.y(), view->point_in_cam.z());
      for (int n = 0; n < weights.count; ++n) {
        if (weights.weight[n] > 0.1 && correspondence_weights[o].minCoeff() > 0.0) ++touches[static_cast<std::size_t>(weights.node[n])];
      }
    }
    const Eigen::Vector3d difference = ViewAlbedo(result.lut, observation.first) - ViewAlbedo(result.lut, observation.second);
    result.summary.correspondence_albedo_differences.Add(difference);
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(difference[c])) continue;
      albedo_squared[c] += difference[c] * difference[c];
      albedo_count[c] += 1.0;
    }
  }
  result.summary.correspondence_albedo_rms =
      (albedo_squared.array() / albedo_count.array().max(1.0)).sqrt().matrix();
  int covered = 0;
  for (int n = 0; n < options.grid.NumNodes(); ++n) {
    const double coverage = std::min(1.0, touches[static_cast<std::size_t>(n)] / 4.0);
    result.coverage.node(n).alpha.setConstant(coverage);
    covered += coverage >= 1.0;
  }
  result.summary.covered_fraction = static_cast<double>(covered) / options.grid.NumNodes();
  for (const PureWaterObservation& observation : observations.pure_water) {
    for (int k = 0; k < options.grid.nz; ++k) {
      const Eigen::Vector3d beta =
          result.lut.Lookup(observation.pixel.x(), observation.pixel.y(), options.grid.SlabDepth(k)).beta;
      result.summary.pure_water_max_violation =
          result.summary.pure_water_max_violation.cwiseMax(beta - observation.intensity);
      result.summary.pure_water_excess.Add(beta - observation.intensity);
    }
  }
  result.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace lutex
