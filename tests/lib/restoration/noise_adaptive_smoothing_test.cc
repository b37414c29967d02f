#include "lib/restoration/noise_adaptive_smoothing.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "lib/geometry/look_at.h"
#include "lib/model/sensor.h"
#include "lib/model/simulator.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/restoration/restorer.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

// A simulated survey frame in turbid coastal water, two cosine lights 0.4 m beside the camera, 2.2 m
// above the synthetic seafloor: restored with the simulator's own LUT, so that what remains is the noise
// restoration amplified (and the shading approximation), against the true albedo.
class TurbidFrame {
 public:
  TurbidFrame()
      : seafloor_(MakeSeafloor()),
        simulator_(seafloor_, testing::TwoCosineLights(0.4, 30.0, 2.0), CoastalWater(),
                   SurfaceAlbedo::FromVertexColors(seafloor_)),
        camera_(Camera::Pinhole(1, 320, 240, 160, 160)),
        rays_(camera_),
        cam_from_world_(CamFromWorldLookingAt(Eigen::Vector3d(0.1, -0.2, 2.2), Eigen::Vector3d(0.05, 0, -1),
                                              Eigen::Vector3d(0, -1, 0))),
        maps_(RaycastScene(seafloor_).Render(rays_, cam_from_world_)),
        lut_(simulator_.TrueLut(camera_, testing::LutGrid(40, 30, 12, 0.5, 4.0, 320, 240))),
        truth_(simulator_.RenderAlbedo(rays_, cam_from_world_)),
        surface_(maps_.depth == maps_.depth) {}

  // Restored albedo of the render, with sensor noise (shot 0.01, read 0.002; seed 3) or without.
  cv::Mat Restored(bool noisy) const {
    cv::Mat image = simulator_.Render(rays_, cam_from_world_);
    if (noisy) {
      SensorOptions sensor;
      sensor.shot_noise = 0.01;
      sensor.read_noise = 0.002;
      sensor.seed = 3;
      image = ApplySensor(image, sensor, 0);
    }
    return RestoreImage(image, maps_, rays_, lut_, RestorationOptions()).albedo;
  }

  // Mean |albedo - truth| over the surface pixels (2 px inside it), all channels; with `edges_only`,
  // over those where the true albedo changes by more than 0.1 within 1 px.
  double MeanError(const cv::Mat& albedo, bool edges_only = false) const {
    double sum = 0.0;
    std::size_t count = 0;
    for (int row = 2; row < albedo.rows - 2; ++row) {
      for (int col = 2; col < albedo.cols - 2; ++col) {
        if (!surface_.at<std::uint8_t>(row, col)) continue;
        if (edges_only && !AtEdge(row, col)) continue;
        for (int c = 0; c < 3; ++c) {
          sum += std::abs(albedo.at<cv::Vec3f>(row, col)[c] - truth_.at<cv::Vec3f>(row, col)[c]);
          ++count;
        }
      }
    }
    EXPECT_GT(count, edges_only ? 3000u : 150000u);
    return sum / static_cast<double>(count);
  }

  const cv::Mat& surface() const { return surface_; }

 private:
  static Mesh MakeSeafloor() {
    SyntheticSeafloorOptions options;
    options.size_x = 7;
    options.size_y = 6;
    options.cell_size = 0.02;
    options.patch_size = 0.25;
    return MakeSyntheticSeafloor(options);
  }
  // Coastal water as in the shared turbid Blender sets: c = 0.85 / 0.5 / 0.62 per metre.
  static Water CoastalWater() {
    Water water;
    water.absorption = Eigen::Vector3d(0.5, 0.1, 0.2);
    water.scattering = Eigen::Vector3d(0.35, 0.4, 0.42);
    return water;
  }
  bool AtEdge(int row, int col) const {
    const cv::Vec3f& centre = truth_.at<cv::Vec3f>(row, col);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (cv::norm(truth_.at<cv::Vec3f>(row + dy, col + dx) - centre, cv::NORM_INF) > 0.1) return true;
      }
    }
    return false;
  }

  Mesh seafloor_;
  Simulator simulator_;
  Camera camera_;
  CameraRays rays_;
  Rigid3d cam_from_world_;
  GeometryMaps maps_;
  FrustumLut lut_;
  cv::Mat truth_;
  cv::Mat surface_;
};

const TurbidFrame& Frame() {
  static const TurbidFrame frame;
  return frame;
}

TEST(NoiseAdaptiveSmoothing, RemovesTheNoiseRestorationAmplifiedWithoutBlurringTheAlbedosEdges) {
  const cv::Mat restored = Frame().Restored(true);
  const cv::Mat smoothed = SmoothNoiseAdaptively(restored, Frame().surface(), NoiseAdaptiveSmoothingOptions());
  const double before = Frame().MeanError(restored), after = Frame().MeanError(smoothed);
  const double edges_before = Frame().MeanError(restored, true), edges_after = Frame().MeanError(smoothed, true);
  // The same window averaged plainly: as much noise gone, the edges smeared.
  cv::Mat box;
  cv::blur(restored, box, cv::Size(5, 5));
  const double edges_box = Frame().MeanError(box, true);
  std::printf("mean error %.4f -> %.4f; at the albedo's edges %.4f -> %.4f (a plain 5 x 5 mean: %.4f)\n", before,
              after, edges_before, edges_after, edges_box);
  EXPECT_LT(after, 0.5 * before);
  EXPECT_LT(edges_after, 0.6 * edges_before);
  EXPECT_LT(edges_after, 0.8 * edges_box);
}

TEST(NoiseAdaptiveSmoothing, EachPassRemovesMoreOfTheNoiseLeftAndKeepsTheEdges) {
  const cv::Mat restored = Frame().Restored(true);
  NoiseAdaptiveSmoothingOptions options;
  double last = Frame().MeanError(restored), last_edges = Frame().MeanError(restored, true);
  for (int passes = 1; passes <= 3; ++passes) {
    options.passes = passes;
    const cv::Mat smoothed = SmoothNoiseAdaptively(restored, Frame().surface(), options);
    const double error = Frame().MeanError(smoothed), edges = Frame().MeanError(smoothed, true);
    std::printf("%d passes: mean error %.4f, at the albedo's edges %.4f\n", passes, error, edges);
    EXPECT_LT(error, 0.97 * last) << passes;
    EXPECT_LT(edges, last_edges) << passes;
    last = error;
    last_edges = edges;
  }
}

TEST(NoiseAdaptiveSmoothing, LeavesANoiseFreeImageAsItWas) {
  const cv::Mat restored = Frame().Restored(false);
  const cv::Mat smoothed = SmoothNoiseAdaptively(restored, Frame().surface(), NoiseAdaptiveSmoothingOptions());
  const double before = Frame().MeanError(restored), after = Frame().MeanError(smoothed);
  cv::Mat box;
  cv::blur(restored, box, cv::Size(5, 5));
  std::printf("noise-free: mean error %.5f -> %.5f (a plain 5 x 5 mean: %.5f)\n", before, after, Frame().MeanError(box));
  EXPECT_LT(after, before + 0.001);
}

TEST(NoiseAdaptiveSmoothing, AnImpulseTakesItsNeighbourhoodsMedian) {
  cv::Mat restored = Frame().Restored(true);
  const cv::Mat clean = Frame().Restored(false);
  restored.at<cv::Vec3f>(120, 160) = cv::Vec3f(5.0f, 5.0f, 5.0f);  // a hot pixel, a firefly
  const cv::Mat smoothed = SmoothNoiseAdaptively(restored, Frame().surface(), NoiseAdaptiveSmoothingOptions());
  const cv::Vec3f value = smoothed.at<cv::Vec3f>(120, 160), truth = clean.at<cv::Vec3f>(120, 160);
  std::printf("impulse: %.3f %.3f %.3f, noise-free %.3f %.3f %.3f\n", value[0], value[1], value[2], truth[0], truth[1],
              truth[2]);
  EXPECT_LT(cv::norm(value - truth, cv::NORM_INF), 0.1);
}

TEST(NoiseAdaptiveSmoothing, AnAbsurdValueStaysFiniteAndLeavesItsNeighboursAlone) {
  cv::Mat albedo(20, 20, CV_32FC3, cv::Scalar::all(0.5));
  const cv::Mat surface(20, 20, CV_8U, cv::Scalar(255));
  cv::RNG rng(2);
  cv::Mat noise(20, 20, CV_32FC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 0.02);
  albedo += noise;
  albedo.at<cv::Vec3f>(10, 10) = cv::Vec3f(3e37f, -3e37f, 3e37f);  // alpha near 0
  const cv::Mat smoothed = SmoothNoiseAdaptively(albedo, surface, NoiseAdaptiveSmoothingOptions());
  EXPECT_TRUE(cv::checkRange(smoothed));
  const cv::Vec3f centre = smoothed.at<cv::Vec3f>(10, 10), beside = smoothed.at<cv::Vec3f>(10, 11);
  EXPECT_LT(cv::norm(centre - cv::Vec3f(0.5f, 0.5f, 0.5f), cv::NORM_INF), 0.1);  // the median of its neighbours
  EXPECT_LT(cv::norm(beside - cv::Vec3f(0.5f, 0.5f, 0.5f), cv::NORM_INF), 0.1);
}

TEST(NoiseAdaptiveSmoothing, PixelsWithoutASurfaceAreNeitherChangedNorUsed) {
  cv::Mat albedo(20, 20, CV_32FC3, cv::Scalar::all(0.5));
  cv::Mat surface(20, 20, CV_8U, cv::Scalar(255));
  surface.colRange(10, 20).setTo(0);
  albedo.colRange(10, 20).setTo(cv::Scalar::all(7.0));
  cv::RNG rng(1);
  cv::Mat noise(20, 10, CV_32FC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 0.05);
  albedo.colRange(0, 10) += noise;
  const cv::Mat smoothed = SmoothNoiseAdaptively(albedo, surface, NoiseAdaptiveSmoothingOptions());
  EXPECT_EQ(cv::norm(smoothed.colRange(10, 20), albedo.colRange(10, 20), cv::NORM_INF), 0.0);
  double worst = 0.0;
  cv::minMaxLoc(smoothed.colRange(0, 10).reshape(1), nullptr, &worst);
  EXPECT_LT(worst, 0.8);  // nothing of the 7.0 beside it leaked in
}

TEST(NoiseAdaptiveSmoothing, RefusesWindowsItCannotUse) {
  const cv::Mat albedo(4, 4, CV_32FC3, cv::Scalar::all(0.5)), surface(4, 4, CV_8U, cv::Scalar(1));
  NoiseAdaptiveSmoothingOptions options;
  options.radius = 0;
  EXPECT_THROW(SmoothNoiseAdaptively(albedo, surface, options), std::invalid_argument);
  options = {};
  options.cutoff = 0.0;
  EXPECT_THROW(SmoothNoiseAdaptively(albedo, surface, options), std::invalid_argument);
  options = {};
  options.passes = 0;
  EXPECT_THROW(SmoothNoiseAdaptively(albedo, surface, options), std::invalid_argument);
  EXPECT_THROW(SmoothNoiseAdaptively(albedo, cv::Mat(4, 4, CV_32F), {}), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
