#include "lib/calibration/cost_functions.h"

#include <memory>
#include <vector>

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

namespace lutex {
namespace {

// Analytic and numeric derivatives agree (the functors are autodiffed; this guards their arithmetic).
void ExpectGradientsAgree(const ceres::CostFunction& cost, std::vector<std::array<double, 2>> values) {
  std::vector<const double*> parameters;
  for (const auto& value : values) parameters.push_back(value.data());
  ceres::NumericDiffOptions numeric;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(&cost, no_manifolds, numeric);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-7, &results)) << results.error_log;
}

// I = 0.5: alpha = 0.8 at both nodes (weights 0.25, 0.75), cos_theta rho = 0.5, beta = 0.1:
// predicted 0.8 * 0.5 + 0.1 = 0.5, so the residual is 0; raising the observation by 0.2 gives -0.2 w.
TEST(CostFunctions, KnownColorHasTheKnownAnswer) {
  const std::unique_ptr<ceres::CostFunction> cost(KnownColorResidual::Create({0.25, 0.75}, {0.25, 0.75}, 0.5, 0.7, 2.0));
  const std::array<double, 2> a{0.8, 0.1}, b{0.8, 0.1};
  const double* parameters[] = {a.data(), b.data()};
  double residual;
  ASSERT_TRUE(cost->Evaluate(parameters, &residual, nullptr));
  EXPECT_NEAR(residual, 2.0 * (0.5 - 0.7), 1e-15);
  ExpectGradientsAgree(*cost, {{0.8, 0.1}, {0.3, 0.05}});
}

TEST(CostFunctions, SmoothnessPenalisesDifferencesOfOneComponent) {
  const std::unique_ptr<ceres::CostFunction> alpha(SmoothnessResidual::Create(0, 3.0));
  const std::unique_ptr<ceres::CostFunction> beta(SmoothnessResidual::Create(1, 3.0));
  const std::array<double, 2> a{1.0, 0.2}, b{0.5, 0.2};
  const double* parameters[] = {a.data(), b.data()};
  double residual;
  ASSERT_TRUE(alpha->Evaluate(parameters, &residual, nullptr));
  EXPECT_DOUBLE_EQ(residual, 1.5);
  ASSERT_TRUE(beta->Evaluate(parameters, &residual, nullptr));
  EXPECT_DOUBLE_EQ(residual, 0.0);
  ExpectGradientsAgree(*alpha, {{1.0, 0.2}, {0.5, 0.3}});
}

// One-sided: no penalty while beta stays under the pure-water value, linear above it.
TEST(CostFunctions, PureWaterBoundIsOneSided) {
  const std::unique_ptr<ceres::CostFunction> cost(PureWaterBoundResidual::Create({0.5, 0.5}, 0.1, 10.0));
  double residual;
  const std::array<double, 2> low{1.0, 0.05}, high{1.0, 0.2};
  const double* below[] = {low.data(), low.data()};
  ASSERT_TRUE(cost->Evaluate(below, &residual, nullptr));
  EXPECT_EQ(residual, 0.0);
  const double* above[] = {high.data(), high.data()};
  ASSERT_TRUE(cost->Evaluate(above, &residual, nullptr));
  EXPECT_NEAR(residual, 10.0 * (0.2 - 0.1), 1e-15);
  ExpectGradientsAgree(*cost, {{1.0, 0.3}, {1.0, 0.25}});
}

}  // namespace
}  // namespace lutex
