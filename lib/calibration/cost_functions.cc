#include "lib/calibration/cost_functions.h"

namespace lutex {
namespace {

constexpr int kStride = 4;

template <typename Functor>
ceres::CostFunction* MakeDynamic(Functor* functor, std::size_t num_nodes) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, kStride>(functor);
  for (std::size_t i = 0; i < num_nodes; ++i) cost->AddParameterBlock(2);
  cost->SetNumResiduals(1);
  return cost;
}

}  // namespace

ceres::CostFunction* KnownColorResidual::Create(std::vector<double> alpha_weights, std::vector<double> beta_weights,
                                                double shading_albedo, double intensity, double weight) {
  const std::size_t count = alpha_weights.size();
  return MakeDynamic(new KnownColorResidual{std::move(alpha_weights), std::move(beta_weights), shading_albedo,
                                            intensity, weight},
                     count);
}

ceres::CostFunction* SmoothnessResidual::Create(int component, double weight, double scale_a, double scale_b) {
  return new ceres::AutoDiffCostFunction<SmoothnessResidual, 1, 2, 2>(
      new SmoothnessResidual{component, weight, scale_a, scale_b});
}

ceres::CostFunction* PureWaterBoundResidual::Create(std::vector<double> beta_weights, double intensity, double weight,
                                                    double reached_fraction, double short_weight) {
  const std::size_t count = beta_weights.size();
  return MakeDynamic(
      new PureWaterBoundResidual{std::move(beta_weights), intensity, weight, reached_fraction, short_weight}, count);
}

ceres::CostFunction* CorrespondenceResidual::Create(std::vector<std::array<double, 4>> coefficients, double cos_theta_1,
                                                    double intensity_1, double cos_theta_2, double intensity_2,
                                                    double weight) {
  const std::size_t count = coefficients.size();
  return MakeDynamic(new CorrespondenceResidual{std::move(coefficients), cos_theta_1, intensity_1, cos_theta_2,
                                                intensity_2, weight},
                     count);
}

}  // namespace lutex
