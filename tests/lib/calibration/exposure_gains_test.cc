#include "lib/calibration/exposure_gains.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

// A LUT like a rig's in water: alpha falls with depth (and towards the image's sides), beta grows with it.
FrustumLut KnownLut() {
  FrustumLut lut(testing::LutGrid(8, 6, 6, 0.5, 4.0, 640, 480));
  const FrustumLutGrid& grid = lut.grid();
  for (int k = 0; k < grid.nz; ++k) {
    const double z = grid.z_near + (grid.z_far - grid.z_near) * k / (grid.nz - 1);
    for (int j = 0; j <= grid.ny; ++j) {
      for (int i = 0; i <= grid.nx; ++i) {
        const double side = 1.0 - 0.3 * std::abs(i - grid.nx / 2.0) / grid.nx;
        lut.node(i, j, k).alpha = Eigen::Vector3d(0.5, 0.8, 0.9) * side / (z * z);
        lut.node(i, j, k).beta = Eigen::Vector3d(0.002, 0.01, 0.015) * z;
      }
    }
  }
  return lut;
}

struct Dive {
  ObservationSet observations;
  std::vector<double> true_gains;
};

// `num_images` images with gains in [0.9, 1.1]; each surface point seen by two images (neighbours in a
// chain, so the chain links them all), with shot noise of 1 %. Known colours in the first
// `known_color_images` images.
Dive SimulatedDive(int num_images, int known_color_images, double outlier_fraction, std::uint64_t seed) {
  const FrustumLut lut = KnownLut();
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Dive dive;
  for (int i = 0; i < num_images; ++i) {
    dive.observations.images.push_back("image_" + std::to_string(i) + ".png");
    dive.true_gains.push_back(0.9 + 0.2 * uniform(random));
  }
  const auto view = [&](int image, const Eigen::Vector3d& albedo) {
    SurfaceView v;
    v.pixel = Eigen::Vector2d(640 * uniform(random), 480 * uniform(random));
    v.point_in_cam = Eigen::Vector3d(0, 0, 1.0 + 2.0 * uniform(random));
    v.cos_theta = 0.6 + 0.4 * uniform(random);
    v.image = image;
    const LutNode node = lut.Lookup(v.pixel.x(), v.pixel.y(), v.point_in_cam.z());
    for (int c = 0; c < 3; ++c) {
      const double value = dive.true_gains[image] * (node.alpha[c] * v.cos_theta * albedo[c] + node.beta[c]);
      v.intensity[c] = value * (1.0 + 0.01 * normal(random));
    }
    return v;
  };
  for (int i = 0; i + 1 < num_images; ++i) {
    for (int n = 0; n < 200; ++n) {
      const Eigen::Vector3d albedo(0.1 + 0.6 * uniform(random), 0.1 + 0.6 * uniform(random), 0.1 + 0.6 * uniform(random));
      CorrespondenceObservation o{view(i, albedo), view(i + 1, albedo), Eigen::Vector3d::Ones()};
      // A mismatch: the second view sees another surface.
      if (uniform(random) < outlier_fraction) o.second = view(i + 1, Eigen::Vector3d(0.9, 0.05, 0.3));
      dive.observations.correspondences.push_back(o);
    }
  }
  for (int i = 0; i < known_color_images; ++i) {
    for (int n = 0; n < 100; ++n) {
      const Eigen::Vector3d albedo(0.2 + 0.5 * uniform(random), 0.2 + 0.5 * uniform(random), 0.2 + 0.5 * uniform(random));
      const SurfaceView v = view(i, albedo);
      KnownColorObservation o;
      o.pixel = v.pixel;
      o.point_in_cam = v.point_in_cam;
      o.cos_theta = v.cos_theta;
      o.intensity = v.intensity;
      o.albedo = albedo;
      o.image = i;
      dive.observations.known_colors.push_back(o);
    }
  }
  return dive;
}

double GeometricMean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double value : values) sum += std::log(value);
  return std::exp(sum / static_cast<double>(values.size()));
}

TEST(ExposureGains, CorrespondencesAloneRecoverTheGainsUpToTheirMean) {
  const Dive dive = SimulatedDive(12, 0, 0.0, 1);
  const ExposureGains fitted = FitExposureGains(dive.observations, KnownLut());
  ASSERT_EQ(fitted.gains.size(), 12u);
  // The gauge: geometric mean 1. The truth on that gauge:
  const double true_mean = GeometricMean(dive.true_gains);
  EXPECT_NEAR(GeometricMean(fitted.gains), 1.0, 1e-9);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_NEAR(fitted.gains[i], dive.true_gains[i] / true_mean, 0.005) << "image " << i;
    EXPECT_FALSE(fitted.fixed_by_known_colors[i]);
    EXPECT_GT(fitted.num_residuals[i], 100u);
  }
}

TEST(ExposureGains, KnownColoursFixTheAbsoluteGains) {
  const Dive dive = SimulatedDive(8, 2, 0.0, 2);
  const ExposureGains fitted = FitExposureGains(dive.observations, KnownLut());
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(fitted.gains[i], dive.true_gains[i], 0.005) << "image " << i;
    EXPECT_TRUE(fitted.fixed_by_known_colors[i]);
  }
}

TEST(ExposureGains, MismatchedCorrespondencesCountLess) {
  const Dive dive = SimulatedDive(8, 0, 0.15, 3);
  const ExposureGains fitted = FitExposureGains(dive.observations, KnownLut());
  const double true_mean = GeometricMean(dive.true_gains);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_NEAR(fitted.gains[i], dive.true_gains[i] / true_mean, 0.01) << "image " << i;
}

TEST(ExposureGains, SeparateGroupsEachHaveMeanOneAndUnseenImagesKeepOne) {
  Dive dive = SimulatedDive(6, 0, 0.0, 4);
  // Cut the chain between images 2 and 3 (each image has 200 correspondences with the next), and add an
  // image nothing sees.
  std::vector<CorrespondenceObservation> kept;
  for (const CorrespondenceObservation& o : dive.observations.correspondences) {
    if (!(o.first.image == 2 && o.second.image == 3)) kept.push_back(o);
  }
  dive.observations.correspondences = kept;
  dive.observations.images.push_back("unseen.png");
  const ExposureGains fitted = FitExposureGains(dive.observations, KnownLut());
  EXPECT_NEAR(GeometricMean({fitted.gains[0], fitted.gains[1], fitted.gains[2]}), 1.0, 1e-9);
  EXPECT_NEAR(GeometricMean({fitted.gains[3], fitted.gains[4], fitted.gains[5]}), 1.0, 1e-9);
  const double first_mean = GeometricMean({dive.true_gains[0], dive.true_gains[1], dive.true_gains[2]});
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(fitted.gains[i], dive.true_gains[i] / first_mean, 0.005);
  EXPECT_EQ(fitted.gains[6], 1.0);
  EXPECT_EQ(fitted.num_residuals[6], 0u);
}

// An image that shows only known colours (a board at one distance) keeps gain 1: its gain would trade
// with the LUT's fall-off there. Images with correspondences are still fitted, absolutely.
TEST(ExposureGains, AnImageWithKnownColoursAloneKeepsGainOne) {
  Dive dive = SimulatedDive(6, 6, 0.0, 6);
  std::vector<CorrespondenceObservation> kept;
  for (const CorrespondenceObservation& o : dive.observations.correspondences) {
    if (o.first.image != 5 && o.second.image != 5) kept.push_back(o);
  }
  dive.observations.correspondences = kept;
  const ExposureGains fitted = FitExposureGains(dive.observations, KnownLut());
  EXPECT_EQ(fitted.gains[5], 1.0);
  EXPECT_EQ(fitted.num_residuals[5], 0u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(fitted.gains[i], dive.true_gains[i], 0.005) << "image " << i;
}

TEST(ExposureGains, DividingThemOutRestoresTheObservationsOfGainOne) {
  Dive dive = SimulatedDive(4, 1, 0.0, 5);
  const Eigen::Vector3d before = dive.observations.correspondences.front().first.intensity;
  const int image = dive.observations.correspondences.front().first.image;
  DivideOutExposureGains(dive.true_gains, &dive.observations);
  EXPECT_TRUE(dive.observations.correspondences.front().first.intensity.isApprox(before / dive.true_gains[image]));
  EXPECT_THROW(DivideOutExposureGains({1.0}, &dive.observations), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
