// Calibration on data the simulator rendered (seeded, noisy, 8-bit sRGB): frames of two flat boards of
// known, widely different colours at 0.7-2.8 m, tilted, in clear water with two spot lights 0.3 m to the
// sides. The recovered LUT is compared with the simulator's true LUT on the nodes the data covers, and a
// held-out view of a third colour is restored and compared with its true albedo.
//
// Status: the bounds below record what the calibrator achieves today (measured: fit RMS 0.004, alpha
// median relative error 11.9 % / p90 37 %, held-out restoration median 1.9 % / p90 5.8 %); they guard
// against regressions. History: with the paper's plain neighbour differences the numbers were 15 % / 90 %
// and 2.9 % / 12 %; smoothing the shape relative to the reference LUT instead removed most of the corner
// and far-slab overshoot.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/calibrator.h"
#include "lib/calibration/known_color_sampling.h"
#include "lib/calibration/pure_water_sampling.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/image/image_io.h"
#include "lib/model/simulator.h"
#include "lib/model/water.h"
#include "lib/restoration/restorer.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

constexpr int kWidth = 160, kHeight = 120;

FrustumLutGrid Grid() { return testing::LutGrid(8, 6, 6, 0.7, 2.8, kWidth, kHeight); }

// A camera looking at the board (the plane z = 0) from `distance`, tilted by `tilt` radians about x.
Rigid3d BoardView(double distance, double tilt) {
  const Eigen::Vector3d forward(0, std::sin(tilt), -std::cos(tilt));
  return CamFromWorldLookingAt(-distance * forward, forward, Eigen::Vector3d(0, -1, 0));
}

// Renders one noisy 8-bit frame (through a PNG round trip) and its geometry.
struct Frame {
  cv::Mat image;
  GeometryMaps maps;
};

Frame Render(const Simulator& simulator, const RaycastScene& scene, const CameraRays& rays, const Rigid3d& pose,
             std::uint64_t index, const testing::TempDir& dir) {
  return {testing::NoisySrgb8Frame(simulator, rays, pose, index, 5, dir.path()), scene.Render(rays, pose)};
}

// Known colours from frames of the board (all of albedo `albedo`, rendered by `simulator`) at 0.7-2.8 m,
// tilted by +-15 degrees; `index` numbers the frames for their noise.
void AddBoardFrames(const Simulator& simulator, const RaycastScene& scene, const CameraRays& rays,
                    const Eigen::Vector3d& albedo, const testing::TempDir& dir, std::uint64_t* index,
                    ObservationSet* observations) {
  for (double distance : {0.7, 0.95, 1.25, 1.6, 2.0, 2.4, 2.8}) {
    for (double tilt : {-0.26, 0.26}) {
      const Frame frame = Render(simulator, scene, rays, BoardView(distance, tilt), (*index)++, dir);
      const cv::Mat known(kHeight, kWidth, CV_32FC3, cv::Scalar(albedo.x(), albedo.y(), albedo.z()));
      for (const KnownColorObservation& observation : SampleKnownColors(frame.image, known, frame.maps, rays)) {
        observations->known_colors.push_back(observation);
      }
    }
  }
}

// A flat board (the plane z = 0), the camera that looks at it, and a folder for the frames.
class Calibrator : public ::testing::Test {
 protected:
  testing::TempDir dir;
  const Mesh board = MakeHeightFieldMesh([](double, double) { return 0.0; }, -10, 10, -10, 10, 2, 2);
  const RaycastScene scene{board};
  const Camera camera = Camera::Pinhole(1, kWidth, kHeight, 100, 100);
  const CameraRays rays{camera};
};

TEST_F(Calibrator, RecoversTheTrueLutFromTwoBoardsAndRestoresAHeldOutView) {
  // sRGB [181, 110, 30] and [80, 160, 90], the shared dataset's boards, linearised.
  const Eigen::Vector3d orange(SrgbToLinear(181 / 255.0), SrgbToLinear(110 / 255.0), SrgbToLinear(30 / 255.0));
  const Eigen::Vector3d green(SrgbToLinear(80 / 255.0), SrgbToLinear(160 / 255.0), SrgbToLinear(90 / 255.0));

  ObservationSet observations;
  std::uint64_t index = 0;
  for (const Eigen::Vector3d& albedo : {orange, green}) {
    const Simulator simulator(board, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(), SurfaceAlbedo::Constant(albedo));
    AddBoardFrames(simulator, scene, rays, albedo, dir, &index, &observations);
  }
  CalibrationOptions options;
  options.grid = Grid();
  options.levels = {{2, 2}, {4, 3}, {8, 6}};
  const Simulator weighting(board, PointLightAtCamera(), testing::ClearWater(), SurfaceAlbedo::Constant(orange));
  const CalibrationResult result = Calibrate(observations, weighting.TrueLut(camera, options.grid), options);

  // Exposure 2 scales the true LUT into image units.
  const Simulator truth(board, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(), SurfaceAlbedo::Constant(orange));
  FrustumLut true_lut = truth.TrueLut(camera, options.grid);
  std::vector<double> alpha_errors, beta_errors;
  for (int n = 0; n < options.grid.NumNodes(); ++n) {
    if (result.coverage.node(n).alpha.x() < 1.0) continue;
    for (int c = 0; c < 3; ++c) {
      alpha_errors.push_back(std::abs(result.lut.node(n).alpha[c] / (2.0 * true_lut.node(n).alpha[c]) - 1.0));
      beta_errors.push_back(std::abs(result.lut.node(n).beta[c] - 2.0 * true_lut.node(n).beta[c]));
    }
  }
  ASSERT_FALSE(alpha_errors.empty());
  std::sort(alpha_errors.begin(), alpha_errors.end());
  std::sort(beta_errors.begin(), beta_errors.end());
  std::printf("observations %zu, covered nodes %.0f %%, rms %.4f %.4f %.4f\n", observations.known_colors.size(),
              100 * result.summary.covered_fraction, result.summary.known_color_rms.x(),
              result.summary.known_color_rms.y(), result.summary.known_color_rms.z());
  std::printf("alpha relative error: median %.4f p90 %.4f; beta absolute error: median %.5f p90 %.5f\n",
              alpha_errors[alpha_errors.size() / 2], alpha_errors[alpha_errors.size() * 9 / 10],
              beta_errors[beta_errors.size() / 2], beta_errors[beta_errors.size() * 9 / 10]);

  // Held out: a grey board at 1.8 m tilted 20 degrees about x.
  const Eigen::Vector3d grey = Eigen::Vector3d::Constant(0.35);
  const Simulator held_out(board, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(), SurfaceAlbedo::Constant(grey));
  const Frame frame = Render(held_out, scene, rays, BoardView(1.8, 0.35), 99, dir);
  const RestoredImage restored = RestoreImage(frame.image, frame.maps, rays, result.lut, RestorationOptions());
  const std::vector<double> errors = testing::SortedConfidentErrors(restored, grey);
  std::printf("held-out restoration: median error %.4f, p90 %.4f over %zu pixel-channels\n", errors[errors.size() / 2],
              errors[errors.size() * 9 / 10], errors.size());
  EXPECT_LT(result.summary.known_color_rms.maxCoeff(), 0.01);  // the fit explains the data to ~1 8-bit level
  EXPECT_GT(result.summary.covered_fraction, 0.9);
  EXPECT_LT(alpha_errors[alpha_errors.size() / 2], 0.16);
  EXPECT_LT(errors[errors.size() / 2], 0.025);
  EXPECT_LT(errors[errors.size() * 9 / 10], 0.08);
}

// In air with one known colour (paper Sec. 4.1-4.2): a white board (albedo 0.8) at 0.5-2.5 m, tilted,
// with a flash 0.1 m to the right of the camera, as in the shared inair_whiteboard data; beta is held at
// 0. A held-out red board must be restored within 3 % (median over its pixels). Shading is computed
// towards the known flash: with the paper's camera-centred shading the fit RMS was 0.0066 and the red
// board's error 5.2 %; with the flash on the camera centre (model exact) 0.0038 and 2.45 %, the noise floor.
TEST_F(Calibrator, InAirOneKnownColourRestoresARedBoard) {
  LightRig flash;
  Light light;
  light.position_in_cam = Eigen::Vector3d(0.1, 0, 0);
  light.intensity = Eigen::Vector3d::Constant(0.3);
  flash.lights.push_back(light);
  const Eigen::Vector3d white = Eigen::Vector3d::Constant(0.8);
  const Simulator simulator(board, flash, Water::Air(), SurfaceAlbedo::Constant(white));
  KnownColorSamplingOptions sampling;
  sampling.shading.light_in_cam = light.position_in_cam;
  ObservationSet observations;
  std::uint64_t index = 200;
  for (double distance : {0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 1.7, 1.9, 2.1, 2.3, 2.5}) {
    for (double tilt : {-0.2, 0.2}) {
      const Frame frame = Render(simulator, scene, rays, BoardView(distance, tilt), index++, dir);
      const cv::Mat known(kHeight, kWidth, CV_32FC3, cv::Scalar(white.x(), white.y(), white.z()));
      for (const KnownColorObservation& observation : SampleKnownColors(frame.image, known, frame.maps, rays, sampling)) {
        observations.known_colors.push_back(observation);
      }
    }
  }
  CalibrationOptions options;
  options.grid = Grid();
  options.grid.z_near = 0.45;
  options.grid.z_far = 2.6;
  options.levels = {{2, 2}, {4, 3}, {8, 6}};
  options.in_air = true;
  options.grid.shading.light_in_cam = light.position_in_cam;
  // The reference is rendered for a point light where shading assumes it.
  LightRig reference_rig = PointLightAtCamera();
  reference_rig.lights[0].position_in_cam = light.position_in_cam;
  const Simulator weighting(board, reference_rig, Water::Air(), SurfaceAlbedo::Constant(white));
  const CalibrationResult result = Calibrate(observations, weighting.TrueLut(camera, options.grid), options);
  for (int n = 0; n < options.grid.NumNodes(); ++n) ASSERT_EQ(result.lut.node(n).beta, Eigen::Vector3d::Zero());

  const Eigen::Vector3d red(0.578, 0.021, 0.021);
  const Simulator held_out(board, flash, Water::Air(), SurfaceAlbedo::Constant(red));
  const Frame frame = Render(held_out, scene, rays, BoardView(1.2, 0.3), 299, dir);
  const RestoredImage restored = RestoreImage(frame.image, frame.maps, rays, result.lut, RestorationOptions());
  std::vector<double> errors;
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      if (restored.confidence.at<cv::Vec3f>(row, col)[0] < 0.5f) continue;
      errors.push_back(std::abs(restored.albedo.at<cv::Vec3f>(row, col)[0] - red.x()));
    }
  }
  ASSERT_GT(errors.size(), 5000u);
  std::sort(errors.begin(), errors.end());
  std::printf("in air: observations %zu, rms %.4f, red board median error %.4f, p90 %.4f\n",
              observations.known_colors.size(), result.summary.known_color_rms.x(), errors[errors.size() / 2],
              errors[errors.size() * 9 / 10]);
  EXPECT_LT(errors[errors.size() / 2], 0.03);
}

// Turbid water, one board colour: known colours of one albedo cannot tell alpha from beta, so nothing but
// the reference sets the level of beta, and the reference here is rendered for clear water (the wrong
// one). Pure water bounds beta from above; with the fraction of it that backscatter reaches at each range
// (here the truth's: the water prior's job is to estimate it, water_prior_test.cc) it bounds beta from
// below as well, and beta comes out near the true level. Measured: median |beta / true beta - 1| over
// the covered nodes 1.00 with the bound alone (beta 0: the clear water's shape of alpha explains the
// board), 0.34 with both (beta 73 % of the truth at 2.8 m: the one colour and the clear-water shape
// still pull it down against the band's lower weight, CalibrationOptions::pure_water_reached_weight).
TEST_F(Calibrator, PureWaterAndTheFractionBackscatterReachesSetBetaWhereOneColourCannot) {
  const Water coastal = *WaterPreset("coastal");
  const LightRig rig = testing::TwoCosineLights(0.3, 1.0, 1.5);
  const Eigen::Vector3d grey = Eigen::Vector3d::Constant(0.35);
  const Simulator truth(board, rig, coastal, SurfaceAlbedo::Constant(grey));

  ObservationSet observations;
  std::uint64_t index = 0;
  AddBoardFrames(truth, scene, rays, grey, dir, &index, &observations);
  const Simulator open_water(Mesh(), rig, coastal, SurfaceAlbedo::Constant(grey));
  for (int frame = 0; frame < 3; ++frame) {
    const cv::Mat image = testing::NoisySrgb8Frame(open_water, rays, BoardView(2.0, 0.0), 100 + frame, 5, dir.path());
    for (const PureWaterObservation& observation : SamplePureWater(image, 8)) observations.pure_water.push_back(observation);
  }

  CalibrationOptions options;
  options.grid = Grid();
  options.levels = {{2, 2}, {4, 3}, {8, 6}};
  const FrustumLut true_lut = truth.TrueLut(camera, options.grid);
  FrustumLut reached(options.grid);
  for (int j = 0; j < options.grid.NodesY(); ++j) {
    for (int i = 0; i < options.grid.NodesX(); ++i) {
      const Eigen::Vector3d to_infinity =
          truth.Backscatter(camera.CamFromImg(true_lut.NodePixel(i, j)).normalized(), SimulatorOptions().max_range);
      for (int k = 0; k < options.grid.nz; ++k) reached.node(i, j, k).beta = true_lut.node(i, j, k).beta.cwiseQuotient(to_infinity);
    }
  }
  const Simulator weighting(board, PointLightAtCamera(), testing::ClearWater(), SurfaceAlbedo::Constant(grey));
  const FrustumLut reference = weighting.TrueLut(camera, options.grid);

  // Median over covered nodes and channels of |beta / (2 true beta) - 1| (exposure 2: NoisySrgb8Frame).
  const auto beta_error = [&](const CalibrationResult& result) {
    std::vector<double> errors;
    for (int n = 0; n < options.grid.NumNodes(); ++n) {
      if (result.coverage.node(n).alpha.x() < 1.0) continue;
      for (int c = 0; c < 3; ++c) errors.push_back(std::abs(result.lut.node(n).beta[c] / (2.0 * true_lut.node(n).beta[c]) - 1.0));
    }
    EXPECT_FALSE(errors.empty());
    std::sort(errors.begin(), errors.end());
    return errors[errors.size() / 2];
  };
  const double bound_only = beta_error(Calibrate(observations, reference, options));
  const double banded = beta_error(Calibrate(observations, reference, options, &reached));
  std::printf("beta median relative error: %.3f with the pure-water bound alone, %.3f with the fraction reached\n",
              bound_only, banded);
  EXPECT_LT(banded, 0.45);
  EXPECT_LT(banded, 0.5 * bound_only);

  // Without pure water the fractions bound nothing.
  ObservationSet boards_only = observations;
  boards_only.pure_water.clear();
  const FrustumLut without = Calibrate(boards_only, reference, options).lut;
  const FrustumLut with_fractions = Calibrate(boards_only, reference, options, &reached).lut;
  for (int n = 0; n < options.grid.NumNodes(); ++n) {
    ASSERT_EQ(with_fractions.node(n).alpha, without.node(n).alpha);
    ASSERT_EQ(with_fractions.node(n).beta, without.node(n).beta);
  }

  FrustumLut elsewhere(testing::LutGrid(4, 3, 6, 0.7, 2.8, kWidth, kHeight));
  EXPECT_THROW(Calibrate(observations, reference, options, &elsewhere), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
