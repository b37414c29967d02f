// Forward scattering on the way to the camera (lib/model/forward_scatter.h): the kernel against a Monte
// Carlo of single scattering with exact geometry, its Gaussian bands against the kernel, and the removal
// against the model it inverts.

#include "lib/model/forward_scatter.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace lutex {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Light leaves a surface point straight towards the camera, d away, and is scattered once at a uniform
// point of its path by a Henyey-Greenstein angle (sampled by inverting its distribution). Seen from the
// camera, it arrives from where its new direction meets the plane through the point: at phi = atan((d - s)
// tan(theta) / d). The fraction arriving within phi0 is what the kernel's energy says (the kernel drops
// the rays sent backwards, and is derived for small angles: within 0.035 here).
TEST(ForwardScatter, TheKernelMatchesAMonteCarloOfSingleScatteringOnTheWayToTheCamera) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double d = 2.0;
  for (const double g : {0.8, 0.9, 0.95}) {
    std::vector<double> angles;
    for (int i = 0; i < 200000; ++i) {
      const double s = d * uniform(random);
      const double xi = uniform(random);
      const double root = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
      const double cos_theta = (1.0 + g * g - root * root) / (2.0 * g);
      if (cos_theta <= 0.0) continue;
      const double tan_theta = std::sqrt(1.0 - cos_theta * cos_theta) / cos_theta;
      angles.push_back(std::atan((d - s) * tan_theta / d));
    }
    for (const double degrees : {1.0, 3.0, 10.0, 30.0, 60.0}) {
      const double phi = degrees * kPi / 180.0;
      double within = 0.0;
      for (const double angle : angles) within += angle <= phi ? 1.0 : 0.0;
      within /= static_cast<double>(angles.size());
      EXPECT_NEAR(ForwardScatterEnergyWithin(phi, g), within, 0.035) << "g " << g << ", " << degrees << " degrees";
    }
    // Most of it is near the pixel, but not all: for g = 0.9 a quarter comes from beyond 10 degrees.
    if (g == 0.9) {
      EXPECT_NEAR(1.0 - ForwardScatterEnergyWithin(10.0 * kPi / 180.0, g), 0.25, 0.03);
    }
  }
}

// One bright pixel in the middle of a wide image (f = 200 px: +-69 degrees), spread by the kernel's
// Gaussians: the energy within r pixels of it is the kernel's within atan(r / f), from a few of the finest
// Gaussian's widths on, and none is lost.
TEST(ForwardScatter, APointIsSpreadAsTheKernelSays) {
  const double focal = 200.0, g = 0.9;
  const ForwardScatterKernel kernel = MakeForwardScatterKernel(g, focal);
  double total_weight = kernel.identity_weight;
  for (const double w : kernel.weight) total_weight += w;
  EXPECT_NEAR(total_weight, 1.0, 1e-9);
  const int size = 1025, centre = size / 2;
  cv::Mat point(size, size, CV_32FC3, cv::Scalar::all(0.0));
  point.at<cv::Vec3f>(centre, centre) = cv::Vec3f(1.0f, 1.0f, 1.0f);
  const cv::Mat spread = ConvolveForwardScatterKernel(point, kernel);
  EXPECT_NEAR(cv::sum(spread)[1], 1.0, 0.01);
  for (const double radius : {20.0, 50.0, 150.0, 400.0}) {
    double within = 0.0;
    for (int row = 0; row < size; ++row) {
      for (int col = 0; col < size; ++col) {
        if (std::hypot(row - centre, col - centre) <= radius) within += spread.at<cv::Vec3f>(row, col)[1];
      }
    }
    EXPECT_NEAR(within, ForwardScatterEnergyWithin(std::atan(radius / focal), g), 0.03) << radius << " px";
  }
}

cv::Mat Range(int rows, int cols, double near, double far) {
  cv::Mat range(rows, cols, CV_32F);
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      range.at<float>(row, col) = static_cast<float>(near + (far - near) * col / (cols - 1));
    }
  }
  return range;
}

// The model conserves energy: a uniform surface at one range is neither changed by scattering nor by its
// removal (away from the mirrored edges, which are exact for a uniform image too).
TEST(ForwardScatter, AUniformSurfaceIsUnchanged) {
  const ForwardScatterKernel kernel = MakeForwardScatterKernel(0.9, 160.0);
  const Eigen::Vector3d b(0.35, 0.4, 0.42);
  const cv::Mat uniform(120, 160, CV_32FC3, cv::Scalar(0.2, 0.5, 0.05));
  const cv::Mat range(120, 160, CV_32F, cv::Scalar(2.5));
  EXPECT_LT(cv::norm(AddForwardScatter(uniform, range, kernel, b), uniform, cv::NORM_INF), 1e-5);
  EXPECT_LT(cv::norm(RemoveForwardScatter(uniform, range, kernel, b), uniform, cv::NORM_INF), 1e-5);
}

// A textured surface seen through turbid water loses contrast (a dark square among bright ones is
// brightened by them); removing the scattering gives the surface's own signal back. Pixels without a
// surface keep their value.
TEST(ForwardScatter, RemovingItGivesATexturedSurfaceItsContrastBack) {
  const int rows = 150, cols = 200;
  cv::Mat signal(rows, cols, CV_32FC3);
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const bool bright = ((row / 25) + (col / 25)) % 2 == 0;
      signal.at<cv::Vec3f>(row, col) = bright ? cv::Vec3f(0.6f, 0.8f, 0.3f) : cv::Vec3f(0.05f, 0.1f, 0.02f);
    }
  }
  cv::Mat range = Range(rows, cols, 1.0, 3.0);
  for (int row = 0; row < 10; ++row) range.row(row).setTo(std::numeric_limits<float>::quiet_NaN());
  const ForwardScatterKernel kernel = MakeForwardScatterKernel(0.9, 160.0);
  const Eigen::Vector3d b(0.35, 0.4, 0.42);
  const cv::Mat observed = AddForwardScatter(signal, range, kernel, b);
  // A dark square's centre far away: a third of its light or more comes from its bright neighbours.
  const cv::Vec3f dark_far = observed.at<cv::Vec3f>(87, 162);
  EXPECT_GT(dark_far[1], 1.3f * 0.1f);
  const cv::Mat restored = RemoveForwardScatter(observed, range, kernel, b);
  cv::Mat error;
  cv::absdiff(restored, signal, error);
  EXPECT_LT(cv::norm(error.rowRange(10, rows), cv::NORM_INF), 0.01);
  EXPECT_EQ(cv::norm(observed.rowRange(0, 10), signal.rowRange(0, 10), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(restored.rowRange(0, 10), observed.rowRange(0, 10), cv::NORM_INF), 0.0);
}

TEST(ForwardScatter, BadCoefficientsAreRefused) {
  ForwardScatter scatter;
  scatter.scattering = Eigen::Vector3d(0.1, -0.1, 0.1);
  EXPECT_THROW(scatter.Check(), std::invalid_argument);
  scatter.scattering = Eigen::Vector3d(0.1, 0.1, 0.1);
  scatter.anisotropy_g = 1.0;
  EXPECT_THROW(scatter.Check(), std::invalid_argument);
  scatter.anisotropy_g = 0.9;
  EXPECT_NO_THROW(scatter.Check());
  EXPECT_THROW(MakeForwardScatterKernel(0.9, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
