#include "lib/calibration/calibration_weights.h"

#include <algorithm>
#include <cmath>

namespace lutex {
namespace {

// Alpha between slabs is compared in the quantity the LUT interpolates (see calibrator.cc): slab k1's
// alpha times (z_k1 / z_k0)^2 for inverse-square interpolation.
double SlabScale(const FrustumLut& lut, int k1, int k0) {
  if (lut.grid().alpha_interpolation != AlphaInterpolation::kInverseSquare) return 1.0;
  const double ratio = lut.grid().SlabDepth(k1) / lut.grid().SlabDepth(k0);
  return ratio * ratio;
}

// Mean absolute difference of one quantity (alpha or beta, per channel) over neighbour pairs.
template <typename Get>
Eigen::Vector3d MeanDifference(const FrustumLut& lut, int k0, int k1, bool within, bool scale_slabs, Get get) {
  const FrustumLutGrid& grid = lut.grid();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (int j = 0; j < grid.NodesY(); ++j) {
    for (int i = 0; i < grid.NodesX(); ++i) {
      if (within) {
        if (i + 1 < grid.NodesX()) {
          sum += (get(lut.node(i + 1, j, k0)) - get(lut.node(i, j, k0))).cwiseAbs();
          ++count;
        }
        if (j + 1 < grid.NodesY()) {
          sum += (get(lut.node(i, j + 1, k0)) - get(lut.node(i, j, k0))).cwiseAbs();
          ++count;
        }
      } else {
        const double scale = scale_slabs ? SlabScale(lut, k1, k0) : 1.0;
        sum += (get(lut.node(i, j, k1)) * scale - get(lut.node(i, j, k0))).cwiseAbs();
        ++count;
      }
    }
  }
  return count ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Zero();
}

// Mean over slab k's nodes of one quantity (per channel).
template <typename Get>
Eigen::Vector3d SlabMean(const FrustumLut& lut, int k, Get get) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int j = 0; j < lut.grid().NodesY(); ++j) {
    for (int i = 0; i < lut.grid().NodesX(); ++i) sum += get(lut.node(i, j, k));
  }
  return sum / (lut.grid().NodesX() * lut.grid().NodesY());
}

}  // namespace

SmoothnessWeights ComputeSmoothnessWeights(const FrustumLut& reference, double scale, double alpha_factor) {
  const FrustumLutGrid& grid = reference.grid();
  double alpha_max = 0.0, beta_max = 0.0;
  for (int n = 0; n < grid.NumNodes(); ++n) {
    alpha_max = std::max(alpha_max, reference.node(n).alpha.maxCoeff());
    beta_max = std::max(beta_max, reference.node(n).beta.maxCoeff());
  }
  const double alpha_floor = std::max(1e-6 * alpha_max, 1e-12), beta_floor = std::max(1e-6 * beta_max, 1e-12);
  const auto alpha = [](const LutNode& node) { return node.alpha; };
  const auto beta = [](const LutNode& node) { return node.beta; };
  const auto weight = [](const Eigen::Vector3d& gradient, double floor, double numerator) {
    return Eigen::Vector3d(numerator / gradient.array().max(floor));
  };
  SmoothnessWeights weights;
  for (int k = 0; k < grid.nz; ++k) {
    weights.alpha_within.push_back(weight(MeanDifference(reference, k, k, true, false, alpha), alpha_floor, scale * alpha_factor));
    weights.beta_within.push_back(weight(MeanDifference(reference, k, k, true, false, beta), beta_floor, scale));
    if (k + 1 < grid.nz) {
      weights.alpha_between.push_back(
          weight(MeanDifference(reference, k, k + 1, false, true, alpha), alpha_floor, scale * alpha_factor));
      weights.beta_between.push_back(weight(MeanDifference(reference, k, k + 1, false, false, beta), beta_floor, scale));
    }
  }
  return weights;
}

KnownColorWeighting::KnownColorWeighting(const FrustumLut& reference) : reference_(reference) {
  for (int k = 0; k < reference.grid().nz; ++k) {
    slab_means_.push_back(SlabMean(reference, k, [](const LutNode& node) { return Eigen::Vector3d(0.7 * node.alpha + node.beta); }));
    slab_alpha_means_.push_back(SlabMean(reference, k, [](const LutNode& node) { return node.alpha; }));
  }
}

Eigen::Vector3d KnownColorWeighting::operator()(const KnownColorObservation& observation) const {
  return ViewWeight(observation.pixel, observation.point_in_cam, observation.cos_theta);
}

Eigen::Vector3d KnownColorWeighting::operator()(const CorrespondenceObservation& observation) const {
  const Eigen::Vector3d first = ViewWeight(observation.first.pixel, observation.first.point_in_cam, observation.first.cos_theta);
  const Eigen::Vector3d second =
      ViewWeight(observation.second.pixel, observation.second.point_in_cam, observation.second.cos_theta);
  const Eigen::Vector3d norm = (first.cwiseAbs2() + second.cwiseAbs2()).cwiseSqrt();
  return (first.cwiseProduct(second).array() / norm.array().max(1e-300)).matrix();
}

Eigen::Vector3d KnownColorWeighting::ViewWeight(const Eigen::Vector2d& pixel, const Eigen::Vector3d& point_in_cam,
                                                double cos_theta) const {
  const FrustumLutGrid& grid = reference_.grid();
  const double z = point_in_cam.z();
  const int slab = std::clamp(static_cast<int>(std::lround(grid.SlabCoordinate(z))), 0, grid.nz - 1);
  const Eigen::Vector3d& mean = slab_means_[static_cast<std::size_t>(slab)];
  const double mean_0_green = std::max(slab_means_[0].y(), 1e-12);
  constexpr double kReferenceSnr = 10.0;  // 20 dB on the first slab's green channel
  // Distance to the nearest node, in node spacings.
  const double gx = pixel.x() / grid.image_width * grid.nx;
  const double gy = pixel.y() / grid.image_height * grid.ny;
  const double gz = grid.SlabCoordinate(z);
  const double node_distance = std::sqrt(std::pow(gx - std::round(gx), 2) + std::pow(gy - std::round(gy), 2) +
                                         std::pow(gz - std::round(gz), 2));
  const double inverse_distance = 1.0 / std::max(node_distance, 0.25);
  const double forward_scatter = std::exp(-point_in_cam.norm());  // 1 / (e^(0.5 d))^2
  const Eigen::Vector3d& alpha_mean = slab_alpha_means_[static_cast<std::size_t>(slab)];
  const Eigen::Vector3d alpha_here = reference_.Lookup(pixel.x(), pixel.y(), z).alpha * std::max(cos_theta, 0.0);
  Eigen::Vector3d weight;
  for (int c = 0; c < 3; ++c) {
    const double mean_c = std::max(mean[c], 1e-12);
    const double shot = 0.01 * std::sqrt(mean_c);
    const double constant = mean_c / (kReferenceSnr * mean_0_green);
    const double slab_snr = mean_c / (shot + constant);
    const double alpha_mean_c = std::max(alpha_mean[c], 1e-12);  // a slab of alpha 0 must not divide by 0
    const double albedo_scale = alpha_mean_c / std::max(alpha_here[c], 0.05 * alpha_mean_c);
    weight[c] = inverse_distance * slab_snr * albedo_scale * forward_scatter;
  }
  return weight;
}

}  // namespace lutex
