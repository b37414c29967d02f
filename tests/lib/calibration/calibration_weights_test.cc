// The known-colour weights (calibration_weights.h) measure an observation's residual as an albedo error:
// w alpha_ref cos_theta is the same wherever the reference puts the observation within a slab and however
// bright it is, so an observation where the reference is dark (a spot's edge, red at range) counts as much
// in albedo as one in the bright centre.

#include <gtest/gtest.h>

#include "lib/calibration/calibration_weights.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

// A reference whose alpha falls tenfold from the image's left column of nodes to its right one, in every
// slab; beta is a small constant.
FrustumLut DarkeningReference() {
  FrustumLut reference(testing::LutGrid(4, 3, 4, 0.5, 5.0, 160, 120));
  const FrustumLutGrid& grid = reference.grid();
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        const double fraction = static_cast<double>(i) / (grid.NodesX() - 1);
        reference.node(i, j, k).alpha = Eigen::Vector3d::Constant(std::pow(0.1, fraction) / (k + 1));
        reference.node(i, j, k).beta = Eigen::Vector3d::Constant(0.001);
      }
    }
  }
  return reference;
}

// An observation on node (i, j) of slab k, seen at cos_theta, of the given intensity.
KnownColorObservation OnNode(const FrustumLut& reference, int i, int j, int k, double cos_theta, double intensity) {
  KnownColorObservation observation;
  observation.pixel = reference.NodePixel(i, j);
  observation.point_in_cam = Eigen::Vector3d(0.0, 0.0, reference.grid().SlabDepth(k));
  observation.cos_theta = cos_theta;
  observation.intensity = Eigen::Vector3d::Constant(intensity);
  return observation;
}

TEST(KnownColorWeighting, TheWeightedResidualIsTheAlbedoErrorWhereverTheReferenceIsDark) {
  const FrustumLut reference = DarkeningReference();
  const KnownColorWeighting weighting(reference);
  const int right = reference.grid().NodesX() - 1;
  for (int k = 0; k < reference.grid().nz; ++k) {
    const KnownColorObservation bright = OnNode(reference, 0, 1, k, 1.0, 0.2);
    const KnownColorObservation dark = OnNode(reference, right, 1, k, 0.5, 0.002);
    const double alpha_bright = reference.node(0, 1, k).alpha.x(), alpha_dark = reference.node(right, 1, k).alpha.x();
    ASSERT_NEAR(alpha_dark / alpha_bright, 0.1, 1e-12);
    const Eigen::Vector3d w_bright = weighting(bright), w_dark = weighting(dark);
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(w_bright[c], 0.0);
      // One unit of albedo error moves the prediction by alpha cos_theta: weighted, it counts the same.
      EXPECT_NEAR(w_dark[c] * alpha_dark * 0.5, w_bright[c] * alpha_bright * 1.0, 1e-9 * w_bright[c] * alpha_bright);
    }
    // The observed intensity does not change the weight (the paper's weight grows with it).
    KnownColorObservation brighter = dark;
    brighter.intensity *= 50.0;
    EXPECT_TRUE(weighting(brighter).isApprox(w_dark, 1e-12));
  }
}

TEST(KnownColorWeighting, AReferenceAlphaOfZeroIsFlooredAtAFractionOfTheSlabsMean) {
  FrustumLut reference = DarkeningReference();
  const int slab = 2, right = reference.grid().NodesX() - 1;
  for (int k = 0; k < reference.grid().nz; ++k) reference.node(right, 1, k).alpha.setZero();
  double alpha_mean = 0.0;
  for (int j = 0; j < reference.grid().NodesY(); ++j) {
    for (int i = 0; i < reference.grid().NodesX(); ++i) alpha_mean += reference.node(i, j, slab).alpha.x();
  }
  alpha_mean /= reference.grid().NodesX() * reference.grid().NodesY();
  const KnownColorWeighting weighting(reference);
  const Eigen::Vector3d w_zero = weighting(OnNode(reference, right, 1, slab, 1.0, 0.01));
  const Eigen::Vector3d w_lit = weighting(OnNode(reference, 0, 1, slab, 1.0, 0.01));
  ASSERT_TRUE(w_zero.allFinite());
  // The weight of a point whose reference alpha is 0.05 of the slab's mean.
  EXPECT_NEAR(w_zero.x() * 0.05 * alpha_mean, w_lit.x() * reference.node(0, 1, slab).alpha.x(), 1e-9 * w_lit.x());
}

}  // namespace
}  // namespace lutex
