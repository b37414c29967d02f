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

// The band: with the fraction reached 0.6 and its weight 3, no penalty between 0.06 and 0.1, linear
// with weight 3 below 0.06 and with weight 10 above 0.1.
TEST(CostFunctions, PureWaterBandPenalisesBetaBelowTheFractionReachedWithItsOwnWeight) {
  const std::unique_ptr<ceres::CostFunction> cost(PureWaterBoundResidual::Create({0.5, 0.5}, 0.1, 10.0, 0.6, 3.0));
  const auto evaluate = [&](double beta) {
    const std::array<double, 2> node{1.0, beta};
    const double* nodes[] = {node.data(), node.data()};
    double residual = 1e9;
    EXPECT_TRUE(cost->Evaluate(nodes, &residual, nullptr));
    return residual;
  };
  EXPECT_EQ(evaluate(0.08), 0.0);
  EXPECT_NEAR(evaluate(0.02), 3.0 * (0.06 - 0.02), 1e-15);
  EXPECT_NEAR(evaluate(0.2), 10.0 * (0.2 - 0.1), 1e-15);
  ExpectGradientsAgree(*cost, {{1.0, 0.03}, {1.0, 0.01}});
}

// Albedo 0.4 seen by view 1 (alpha 0.8, beta 0.1, cos 0.5 -> I1 = 0.26) and view 2 (alpha 0.3, beta 0.05,
// cos 1 -> I2 = 0.17), view 1 on node a only, view 2 half on a and half on b: the residual is 0 at the
// truth, and 0 too at the trivial solutions alpha = 0 and beta = I (why the calibration needs a gauge and
// pure-water bounds without targets).
TEST(CostFunctions, CorrespondenceVanishesAtTheTruthAndAtTheTrivialSolutions) {
  // Node a: alpha 0.8 beta 0.1; node b chosen so that 0.5 a + 0.5 b = (0.3, 0.05): b = (-0.2, 0.0).
  const std::unique_ptr<ceres::CostFunction> cost(
      CorrespondenceResidual::Create({{1.0, 1.0, 0.5, 0.5}, {0.0, 0.0, 0.5, 0.5}}, 0.5, 0.26, 1.0, 0.17, 3.0));
  const auto evaluate = [&](std::array<double, 2> a, std::array<double, 2> b) {
    const double* parameters[] = {a.data(), b.data()};
    double residual = 1e9;
    EXPECT_TRUE(cost->Evaluate(parameters, &residual, nullptr));
    return residual;
  };
  EXPECT_NEAR(evaluate({0.8, 0.1}, {-0.2, 0.0}), 0.0, 1e-15);
  EXPECT_NEAR(evaluate({0.0, 0.1}, {0.0, 0.0}), 0.0, 1e-15);
  EXPECT_NEAR(evaluate({0.8, 0.26}, {-0.2, 0.08}), 0.0, 1e-15);
  // Doubling view 1's alpha halves its albedo: 3 * (0.3 * 1 * 0.16 - 1.6 * 0.5 * 0.12) = -0.144.
  EXPECT_NEAR(evaluate({1.6, 0.1}, {-1.0, 0.0}), 3.0 * (0.3 * 0.16 - 1.6 * 0.5 * 0.12), 1e-12);
  ExpectGradientsAgree(*cost, {{0.8, 0.1}, {0.3, 0.05}});
}

}  // namespace
}  // namespace lutex
