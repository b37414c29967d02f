#include "texturing/seam_levelling_system.h"

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace lutex {
namespace {

// A random system of 40 unknowns: a strip of faces whose chart edges repeat (shared by two faces) and
// tie to vertices without unknowns, and 60 seam points; the same terms written into a dense matrix.
struct RandomSystem {
  SeamLevellingSystem system{40, 0.01, 0.1};
  Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(40, 40) * 0.01;
  Eigen::MatrixXd edges_dense;  // fade and edges only

  explicit RandomSystem(unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> unknown(-1, 39);
    const auto edge = [&](int i, int j) {
      system.AddEdge(i, j);
      if (i >= 0) dense(i, i) += 0.1;
      if (j >= 0) dense(j, j) += 0.1;
      if (i >= 0 && j >= 0) {
        dense(i, j) -= 0.1;
        dense(j, i) -= 0.1;
      }
    };
    for (int f = 0; f < 38; ++f) {  // faces (f, f + 1, f + 2): their edges f -> f + 1 are shared
      edge(f, f + 1);
      edge(f + 1, f + 2);
      edge(f + 2, f);
    }
    for (int k = 0; k < 10; ++k) edge(unknown(random), -1);
    system.FinishEdges();
    edges_dense = dense;
    std::uniform_real_distribution<double> weight(0.1, 1.0);
    for (int k = 0; k < 60; ++k) {
      std::array<int, 4> u;
      std::vector<int> all(40);
      for (int i = 0; i < 40; ++i) all[i] = i;
      std::shuffle(all.begin(), all.end(), random);
      for (int r = 0; r < 4; ++r) u[r] = all[r];
      const float t = std::array<float, 3>{0.25f, 0.5f, 0.75f}[k % 3];
      const double w = weight(random);
      system.AddPoint(u, t, w);
      const std::array<double, 4> c{1.0 - t, t, -(1.0 - t), -t};
      for (int r = 0; r < 4; ++r) {
        for (int s = 0; s < 4; ++s) dense(u[r], u[s]) += w * c[r] * c[s];
      }
    }
  }
};

TEST(SeamLevellingSystem, AppliesTheMatrixItsTermsMakeWithoutFormingIt) {
  const RandomSystem random(1);
  ChannelVectors x = ChannelVectors::Random(40, 3), y;
  random.system.Apply(x, &y);
  const Eigen::MatrixXd expected = random.dense * x;
  EXPECT_LT((Eigen::MatrixXd(y) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SeamLevellingSystem, SolvesEachChannelAsADenseFactorisationDoes) {
  const RandomSystem random(2);
  const ChannelVectors b = ChannelVectors::Random(40, 3);
  ChannelVectors x;
  const int iterations = random.system.Solve(b, 1000, 1e-10, &x);
  const Eigen::MatrixXd expected = random.dense.ldlt().solve(Eigen::MatrixXd(b));
  EXPECT_LT((Eigen::MatrixXd(x) - expected).cwiseAbs().maxCoeff(), 1e-7 * expected.cwiseAbs().maxCoeff());
  EXPECT_GT(iterations, 1);
  EXPECT_LE(iterations, 40 + 5);  // CG ends in about n steps in exact arithmetic
}

TEST(SeamLevellingSystem, AChannelWithNothingToSolveStaysZeroWhileTheOthersAreSolved) {
  const RandomSystem random(3);
  ChannelVectors b = ChannelVectors::Random(40, 3);
  b.col(1).setZero();
  ChannelVectors x;
  random.system.Solve(b, 1000, 1e-10, &x);
  EXPECT_EQ(x.col(1).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixXd expected = random.dense.ldlt().solve(Eigen::MatrixXd(b));
  EXPECT_LT((Eigen::MatrixXd(x) - expected).cwiseAbs().maxCoeff(), 1e-7 * expected.cwiseAbs().maxCoeff());
}

TEST(SeamLevellingSystem, ClearingThePointsLeavesTheEdgesAndTheFade) {
  RandomSystem random(4);
  random.system.ClearPoints();
  const ChannelVectors x = ChannelVectors::Random(40, 3);
  ChannelVectors y;
  random.system.Apply(x, &y);
  const Eigen::MatrixXd expected = random.edges_dense * x;
  EXPECT_LT((Eigen::MatrixXd(y) - expected).cwiseAbs().maxCoeff(), 1e-12);
  // and the solve uses the diagonal without the points too
  ChannelVectors solution;
  random.system.Solve(ChannelVectors(x), 1000, 1e-10, &solution);
  const Eigen::MatrixXd solved = random.edges_dense.ldlt().solve(Eigen::MatrixXd(x));
  EXPECT_LT((Eigen::MatrixXd(solution) - solved).cwiseAbs().maxCoeff(), 1e-7 * solved.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace lutex
