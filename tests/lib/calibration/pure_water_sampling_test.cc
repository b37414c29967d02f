// Screening of pure-water images: frames of open water pass, a frame with a surface in view is caught,
// on the project's own simulator (noisy 8-bit) and on the shared Blender renders.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/pure_water_sampling.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/image/image_io.h"
#include "lib/model/light_rig.h"
#include "lib/model/sensor.h"
#include "lib/model/simulator.h"
#include "lib/model/water.h"
#include "tests/support/shared_datasets.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

cv::Mat NoisyFrame(const Simulator& simulator, const CameraRays& rays, const Rigid3d& pose, std::uint64_t index) {
  SensorOptions sensor;
  sensor.exposure = 4.0;
  sensor.shot_noise = 0.01;
  sensor.read_noise = 0.002;
  sensor.seed = 11;
  // Through 8-bit sRGB, as a camera's JPEG would be.
  const cv::Mat linear = ApplySensor(simulator.Render(rays, pose), sensor, index);
  return DecodeLinearImage(EncodeLinearImage(linear, ImageEncoding::kSrgb8), ImageEncoding::kSrgb8);
}

TEST(PureWaterSampling, SimulatedOpenWaterPassesAndAFrameWithTheSeafloorIsCaught) {
  const Camera camera = Camera::Pinhole(1, 160, 120, 100, 100);
  const CameraRays rays(camera);
  const Simulator water(Mesh(), testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(),
                        SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.3)));
  const Mesh floor = MakeHeightFieldMesh([](double, double) { return 0.0; }, -10, 10, -10, 10, 2, 2);
  const Simulator seafloor(floor, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(),
                           SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.3)));
  std::vector<PureWaterImageStats> stats;
  for (std::uint64_t index = 0; index < 4; ++index) {
    const Rigid3d pose = CamFromWorldLookingAt(Eigen::Vector3d(0.1 * static_cast<double>(index), 0, 3), Eigen::Vector3d(0, 0.2, 1),
                                               Eigen::Vector3d(0, -1, 0));
    stats.push_back(MeasurePureWaterImage(NoisyFrame(water, rays, pose, index)));
  }
  // The floor 2.5 m below a camera looking down at it.
  const Rigid3d floor_pose = CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 2.5), Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(0, 1, 0));
  stats.push_back(MeasurePureWaterImage(NoisyFrame(seafloor, rays, floor_pose, 9)));
  for (const PureWaterImageStats& image : stats) {
    std::printf("structure %.4f mean %.5f %.5f %.5f\n", image.structure, image.mean.x(), image.mean.y(), image.mean.z());
  }
  const std::vector<std::string> reasons = ScreenPureWaterImages(stats, PureWaterScreeningOptions());
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(reasons[i].empty()) << i << ": " << reasons[i];
  EXPECT_FALSE(reasons[4].empty());
}

// Harbour water (attenuation 1.4-1.6 per m) under two wide spots beside the camera, exposed as a camera
// set for this water would be: its brightest channel at 0.35 of full scale at the 99th percentile, 8-bit.
// The backscatter is then bright, clean and curved, steepest where the beams enter at the image's sides;
// a Gaussian-smoothed copy left 5-6 % of it as "structure" and every frame was rejected. The seafloor
// (cells of two colours, 25 cm) seen through the same water at 0.8 m is structure (at 1.8 m this water
// lets through too little of it to tell it from open water: 0.5 % of the light, about 1 % brighter).
TEST(PureWaterSampling, WellExposedHarbourWaterPassesAndItsSeafloorIsStructure) {
  const Camera camera = Camera::Pinhole(1, 320, 240, 160, 160);
  const CameraRays rays(camera);
  Water harbour;
  harbour.absorption = Eigen::Vector3d(0.6, 0.35, 0.75);
  harbour.scattering = Eigen::Vector3d(0.8, 0.9, 0.85);
  harbour.anisotropy_g = 0.92;
  LightRig rig;
  for (const double x : {-0.4, 0.4}) {
    Light spot;
    spot.position_in_cam = Eigen::Vector3d(x, 0.0, 0.0);
    spot.intensity = Eigen::Vector3d::Constant(1.2);
    spot.profile = BeamProfile::kCyclesSpot;
    spot.spot_size_rad = 110.0 * M_PI / 180.0;
    spot.spot_blend = 0.5;
    rig.lights.push_back(spot);
  }
  const Simulator water(Mesh(), rig, harbour, SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.3)));
  Mesh floor = MakeHeightFieldMesh([](double, double) { return 0.0; }, -4, 4, -4, 4, 32, 32);
  for (std::size_t f = 0; f < floor.faces.size(); ++f) {
    const bool dark = ((f / 2) % 32 + (f / 2) / 32) % 2 == 0;
    floor.face_colors.push_back(dark ? Eigen::Matrix<std::uint8_t, 3, 1>(40, 60, 50) : Eigen::Matrix<std::uint8_t, 3, 1>(200, 180, 150));
  }
  const Simulator seafloor(floor, rig, harbour, SurfaceAlbedo::FromFaceColors(floor));
  const Rigid3d open_pose = CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0, 0.2, 1), Eigen::Vector3d(0, -1, 0));
  const Rigid3d floor_pose = CamFromWorldLookingAt(Eigen::Vector3d(0.1, 0.1, 0.8), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 1, 0));
  const cv::Mat open_radiance = water.Render(rays, open_pose);
  // The exposure a camera set for this water gives: the brightest channel's 99th percentile at 0.35.
  std::vector<float> values(open_radiance.begin<float>(), open_radiance.end<float>());
  const std::size_t p99 = values.size() * 99 / 100;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(p99), values.end());
  SensorOptions sensor;
  sensor.exposure = 0.35 / values[p99];
  sensor.shot_noise = 0.01;
  sensor.read_noise = 0.002;
  sensor.seed = 5;
  const auto frame = [&](const cv::Mat& radiance, std::uint64_t index) {
    return DecodeLinearImage(EncodeLinearImage(ApplySensor(radiance, sensor, index), ImageEncoding::kSrgb8),
                             ImageEncoding::kSrgb8);
  };
  std::vector<PureWaterImageStats> stats;
  for (std::uint64_t index = 0; index < 3; ++index) stats.push_back(MeasurePureWaterImage(frame(open_radiance, index)));
  const PureWaterImageStats floor_stats = MeasurePureWaterImage(frame(seafloor.Render(rays, floor_pose), 9));
  for (const PureWaterImageStats& image : stats) {
    std::printf("open water: structure %.4f mean %.4f %.4f %.4f\n", image.structure, image.mean.x(), image.mean.y(), image.mean.z());
  }
  std::printf("seafloor: structure %.4f mean %.4f %.4f %.4f\n", floor_stats.structure, floor_stats.mean.x(), floor_stats.mean.y(),
              floor_stats.mean.z());
  const std::vector<std::string> reasons = ScreenPureWaterImages(stats, PureWaterScreeningOptions());
  for (std::size_t i = 0; i < stats.size(); ++i) EXPECT_TRUE(reasons[i].empty()) << i << ": " << reasons[i];
  EXPECT_GT(floor_stats.structure, PureWaterScreeningOptions().max_structure);
}

// In clear and in turbid water, whose backscatter has strong gradients and Monte Carlo fireflies (1.1 to
// 1.5 % of the pixels departed from the smooth fit before the median, and every frame was rejected).
TEST(PureWaterSampling, BlenderPureWaterPassesAndBoardFramesAreCaughtInClearAndTurbidWater) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  for (const std::string water : {"clear", "turbid"}) {
    std::vector<PureWaterImageStats> stats;
    std::vector<std::string> names;
    for (const std::string& dataset : {"purewater_" + water, "calib_boards_" + water}) {
      std::vector<fs::path> images;
      for (const auto& entry : fs::directory_iterator(*dev / dataset / "images")) images.push_back(entry.path());
      std::sort(images.begin(), images.end());
      // All pure-water frames, and board frames mixed in: each board at 0.5 m and at 1.2 m. (Farther, in
      // the turbid water, a board 2 m away whose edge is in a corner is 1.7 times as bright as open water
      // and no edge survives the blur: it passes, and bounds backscatter loosely but validly.)
      const bool pure = dataset.rfind("purewater", 0) == 0;
      const std::vector<std::size_t> chosen = pure ? std::vector<std::size_t>{0, 1, 2, 3} : std::vector<std::size_t>{0, 4, 12, 16};
      for (std::size_t i : chosen) {
        const fs::path path = images.at(i);
        stats.push_back(MeasurePureWaterImage(ReadLinearImage(path, ImageEncoding::kLinear16)));
        names.push_back(dataset + "/" + path.filename().string());
      }
    }
    const std::vector<std::string> reasons = ScreenPureWaterImages(stats, PureWaterScreeningOptions());
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::printf("%s: structure %.4f %s\n", names[i].c_str(), stats[i].structure, reasons[i].c_str());
      EXPECT_EQ(reasons[i].empty(), names[i].rfind("purewater", 0) == 0) << names[i] << ": " << reasons[i];
    }
  }
}

// The turbid seafloor in view is structure, not noise, however smooth the water around it.
TEST(PureWaterSampling, TheTurbidSeafloorIsStructure) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  const PureWaterImageStats seafloor =
      MeasurePureWaterImage(ReadLinearImage(*dev / "seafloor_turbid" / "images" / "frame_0000.png", ImageEncoding::kLinear16));
  std::printf("seafloor_turbid/frame_0000.png: structure %.4f\n", seafloor.structure);
  EXPECT_GT(seafloor.structure, PureWaterScreeningOptions().max_structure);
}

TEST(PureWaterSampling, SamplesEveryStrideThPixelAtItsCentre) {
  cv::Mat image(10, 12, CV_32FC3, cv::Scalar(0.1, 0.2, 0.3));
  image.at<cv::Vec3f>(2, 6) = cv::Vec3f(0.5f, 0.6f, 0.7f);
  const std::vector<PureWaterObservation> samples = SamplePureWater(image, 4);
  ASSERT_EQ(samples.size(), 6u);  // rows 2 and 6, columns 2, 6 and 10
  EXPECT_EQ(samples[1].pixel, Eigen::Vector2d(6.5, 2.5));
  EXPECT_NEAR(samples[1].intensity.z(), 0.7, 1e-7);
  EXPECT_NEAR(samples[0].intensity.z(), 0.3, 1e-7);
}

}  // namespace
}  // namespace lutex
