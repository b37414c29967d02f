#include "lib/calibration/solve_plausibility.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

FrustumLut ConstantLut(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta) {
  FrustumLutGrid grid;
  grid.nx = 4;
  grid.ny = 3;
  grid.nz = 3;
  grid.image_width = 160;
  grid.image_height = 120;
  FrustumLut lut(grid);
  for (int n = 0; n < grid.NumNodes(); ++n) {
    lut.node(n).alpha = alpha;
    lut.node(n).beta = beta;
  }
  return lut;
}

// Observations of known albedo rendered by the image formation `lut` stands for: I = alpha cos rho + beta,
// alpha and beta looked up at the observation as restoration does.
ObservationSet Observed(const FrustumLut& lut) {
  ObservationSet observations;
  for (int i = 0; i < 50; ++i) {
    KnownColorObservation o;
    o.pixel = Eigen::Vector2d(10 + 2 * i, 20 + i);
    o.point_in_cam = Eigen::Vector3d(0.1, 0.0, 1.0 + 0.05 * i);
    o.cos_theta = 0.6 + 0.008 * i;
    o.albedo = Eigen::Vector3d(0.2 + 0.01 * i, 0.5, 0.05 + 0.002 * i);
    const LutNode node = lut.Lookup(o.pixel.x(), o.pixel.y(), o.point_in_cam.z());
    o.intensity = (node.alpha.array() * o.cos_theta * o.albedo.array() + node.beta.array()).matrix();
    observations.known_colors.push_back(o);
  }
  CorrespondenceObservation pair;
  pair.first = {Eigen::Vector2d(40, 40), Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0.2, 0.2, 0.2), 0.9};
  pair.second = {Eigen::Vector2d(90, 70), Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0.15, 0.15, 0.15), 0.7};
  observations.correspondences.push_back(pair);
  return observations;
}

TEST(SolvePlausibility, TheTrueLutRestoresItsObservationsToTheirAlbedo) {
  const Eigen::Vector3d alpha(0.8, 0.5, 0.3), beta(0.01, 0.02, 0.04);
  const FrustumLut lut = ConstantLut(alpha, beta);
  const RestoredObservationStats stats = RestoreObservations(lut, Observed(lut));
  EXPECT_EQ(stats.count, 52u);  // 50 known colours, both views of one correspondence
  EXPECT_EQ(stats.implausible_fraction, Eigen::Vector3d::Zero());
  EXPECT_NEAR(stats.median_albedo.y(), 0.5, 1e-9);  // every known colour has green 0.5
  EXPECT_NO_THROW(CheckSolveIsPlausible(stats));
}

TEST(SolvePlausibility, ADivergedSolveIsRefusedNamingTheChannel) {
  const Eigen::Vector3d alpha(0.8, 0.5, 0.3), beta(0.01, 0.02, 0.04);
  const ObservationSet observations = Observed(ConstantLut(alpha, beta));
  // Blue alpha driven towards 0: the blue albedo of every observation explodes.
  const RestoredObservationStats tiny_alpha =
      RestoreObservations(ConstantLut(Eigen::Vector3d(0.8, 0.5, 1e-4), beta), observations);
  EXPECT_GT(tiny_alpha.implausible_fraction.z(), 0.9);
  EXPECT_EQ(tiny_alpha.implausible_fraction.x(), 0.0);
  try {
    CheckSolveIsPlausible(tiny_alpha);
    FAIL() << "a diverged solve passed";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("diverged"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("blue channel"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("no LUT was written"), std::string::npos) << error.what();
  }
  // Red beta above every signal: negative albedos.
  const RestoredObservationStats high_beta =
      RestoreObservations(ConstantLut(alpha, Eigen::Vector3d(5.0, 0.02, 0.04)), observations);
  EXPECT_GT(high_beta.implausible_fraction.x(), 0.9);
  EXPECT_LT(high_beta.median_albedo.x(), 0.0);
  EXPECT_THROW(CheckSolveIsPlausible(high_beta), std::runtime_error);
  // A few implausible observations (noise, a saturated patch) are not divergence.
  RestoredObservationStats few;
  few.count = 100;
  few.implausible_fraction = Eigen::Vector3d(0.05, 0.0, 0.1);
  EXPECT_NO_THROW(CheckSolveIsPlausible(few));
}

// Where backscatter swamps the signal (blue: alpha cos_theta below 1 under a backscatter of 100), 10 % too
// little beta restores every observation far outside the bounds, but the data could not have pinned it:
// with the water prior (here the truth) saying so, those observations are not judged. A diverged alpha
// where the prior sees signal is still refused.
TEST(SolvePlausibility, ObservationsWhoseSignalIsBelowFivePercentOfTheirIntensityAreNotJudged) {
  const Eigen::Vector3d alpha(0.8, 0.5, 0.3), beta(0.01, 0.02, 100.0);
  const FrustumLut truth = ConstantLut(alpha, beta);
  ObservationSet observations = Observed(truth);
  observations.correspondences.clear();  // their intensities are not rendered with `truth`
  const FrustumLut low_blue_beta = ConstantLut(alpha, Eigen::Vector3d(0.01, 0.02, 90.0));
  const RestoredObservationStats unjudged = RestoreObservations(low_blue_beta, observations);
  EXPECT_GT(unjudged.implausible_fraction.z(), 0.9);
  EXPECT_THROW(CheckSolveIsPlausible(unjudged), std::runtime_error);
  const RestoredObservationStats judged = RestoreObservations(low_blue_beta, observations, &truth);
  EXPECT_EQ(judged.judged_fraction.z(), 0.0);
  EXPECT_EQ(judged.judged_fraction.x(), 1.0);
  EXPECT_EQ(judged.implausible_fraction, Eigen::Vector3d::Zero());
  EXPECT_NO_THROW(CheckSolveIsPlausible(judged));

  const FrustumLut tiny_red_alpha = ConstantLut(Eigen::Vector3d(1e-4, 0.5, 0.3), beta);
  const RestoredObservationStats diverged = RestoreObservations(tiny_red_alpha, observations, &truth);
  EXPECT_GT(diverged.implausible_fraction.x(), 0.9);
  EXPECT_THROW(CheckSolveIsPlausible(diverged), std::runtime_error);
  // A prior with no signal in red (its fit explained red by backscatter alone) says nothing: red is judged.
  const FrustumLut no_red_signal = ConstantLut(Eigen::Vector3d(0.0, 0.5, 0.3), beta);
  const RestoredObservationStats unknown = RestoreObservations(tiny_red_alpha, observations, &no_red_signal);
  EXPECT_EQ(unknown.judged_fraction.x(), 1.0);
  EXPECT_THROW(CheckSolveIsPlausible(unknown), std::runtime_error);
}

}  // namespace
}  // namespace lutex
