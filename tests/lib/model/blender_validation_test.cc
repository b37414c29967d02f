// lutex's simulator against Blender Cycles, an independent physically based path tracer, on the shared
// dev datasets: the same frames rendered from the same metadata (poses, mesh, light rig, water). The
// albedo is taken per pixel from Blender's own albedo pass (radiance is linear in albedo, so
// lutex = black + albedo * (white - black) with renders at albedo 0 and 1), which isolates lighting and
// water from texture sampling. Reports, per dataset, the median relative difference over pixels with
// signal, and asserts the bound justified below. Skips when ../shared/datasets is absent.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "lib/image/image_io.h"
#include "lib/model/simulator.h"
#include "tests/support/blender_dataset.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

struct Comparison {
  std::size_t frames = 0;
  std::vector<double> relative[3];  // (lutex - blender) / blender per channel, pixels with signal
};

double Median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Pixels with signal: above Monte Carlo noise and below clipping. Pure water holds only backscatter,
// 1e-4 to 1e-3 in these renders (its rare brighter pixels are fireflies), so its floor is lower.
Comparison Compare(const testing::BlenderDataset& dataset) {
  const float floor = dataset.kind == "purewater" ? 1e-4f : 0.01f;
  Comparison comparison;
  const SurfaceAlbedo white = SurfaceAlbedo::Constant(Eigen::Vector3d::Ones());
  const SurfaceAlbedo black = SurfaceAlbedo::Constant(Eigen::Vector3d::Zero());
  SimulatorOptions options;
  options.max_range = 60.0;  // the water is a 120 m cube around the scene (metadata water.extent)
  const Simulator lit(dataset.mesh, dataset.rig, dataset.water, white, options);
  const Simulator dark(dataset.mesh, dataset.rig, dataset.water, black, options);
  const Camera& camera = dataset.model.cameras.begin()->second;
  const CameraRays rays(camera);
  const BackscatterTable backscatter = lit.MakeBackscatterTable(rays);
  for (const auto& [id, image] : dataset.model.images) {
    const std::string stem = fs::path(image.name).stem().string();
    const cv::Mat blender = ReadLinearImage(dataset.root / "images" / image.name, ImageEncoding::kLinear16);
    const cv::Mat albedo = ReadLinearImage(dataset.root / "gt" / "albedo" / (stem + ".exr"), ImageEncoding::kFloat);
    const cv::Mat with_white = lit.Render(rays, backscatter, image.cam_from_world);
    const cv::Mat with_black = dark.Render(rays, backscatter, image.cam_from_world);
    for (int row = 0; row < blender.rows; ++row) {
      for (int col = 0; col < blender.cols; ++col) {
        const cv::Vec3f b = blender.at<cv::Vec3f>(row, col), a = albedo.at<cv::Vec3f>(row, col);
        const cv::Vec3f w = with_white.at<cv::Vec3f>(row, col), k = with_black.at<cv::Vec3f>(row, col);
        for (int c = 0; c < 3; ++c) {
          if (!(b[c] > floor && b[c] < 0.99f)) continue;
          const double ours = k[c] + a[c] * (w[c] - k[c]);
          comparison.relative[c].push_back((ours - b[c]) / b[c]);
        }
      }
    }
    ++comparison.frames;
  }
  return comparison;
}

// Bounds. In air the two renderers must agree to 1 % (light units and spot profile are the same; what
// remains is Monte Carlo noise and 1 cm soft shadows). In water lutex attenuates the direct paths by the
// beam attenuation c = a + b, removing all scattered light, while Cycles (one volume bounce) adds back
// light scattered once onto the light-to-surface and surface-to-camera paths; with g = 0.88 most of it
// stays near the direct path. That makes lutex 3-8 % darker on surfaces (more in blue and green, whose b
// is larger, and on the longer seafloor paths). The similarity approximation c' = a + b (1 - g), which
// returns all forward-scattered light, overshoots by 3-11 % on the same frames (README), so the truth is
// bracketed; the bound in water is 10 %. Measured values are printed for the README.
constexpr double kAirBound = 0.01;
constexpr double kWaterBound = 0.10;
TEST(BlenderValidation, SimulatorMatchesCyclesOnTheDevDatasets) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  std::printf("%-20s %7s %10s %10s %10s %10s\n", "dataset", "frames", "pixels", "median R", "median G", "median B");
  for (const char* name : {"calib_boards_clear", "checker_clear", "seafloor_clear", "purewater_clear", "inair_whiteboard"}) {
    if (!fs::is_directory(*dev / name)) continue;
    const Comparison comparison = Compare(testing::LoadBlenderDataset(*dev / name));
    double medians[3];
    std::size_t pixels = 0;
    for (int c = 0; c < 3; ++c) {
      medians[c] = Median(comparison.relative[c]);
      pixels += comparison.relative[c].size();
    }
    std::printf("%-20s %7zu %10zu %+9.2f%% %+9.2f%% %+9.2f%%\n", name, comparison.frames, pixels, 100 * medians[0],
                100 * medians[1], 100 * medians[2]);
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(comparison.relative[c].size(), 1000u) << name << ": too few pixels with signal to compare";
      EXPECT_LT(std::abs(medians[c]), name == std::string("inair_whiteboard") ? kAirBound : kWaterBound)
          << name << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace lutex
