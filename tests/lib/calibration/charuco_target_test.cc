// A ChArUco board with coloured patches as the only calibration target, on frames the simulator rendered
// (8-bit sRGB, noisy; clear water, two lights 0.3 m to the sides): OpenCV finds the board from its markers,
// its pose matches the truth, the known colours land exactly on the rendered patches and black squares,
// and the LUT calibrated from them alone restores a held-out grey board.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/charuco_target.h"
#include "lib/calibration/known_color_sampling.h"
#include "lib/geometry/look_at.h"
#include "lib/image/image_io.h"
#include "lib/model/simulator.h"
#include "tests/support/charuco_board.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

constexpr int kWidth = 640, kHeight = 480;

TEST(CharucoTarget, ReadsTheFileAndRejectsNonsense) {
  testing::TempDir dir;
  const auto path = dir.path() / "board.json";
  std::ofstream(path) << R"({"charuco": {"squares": [6, 4], "square_size": 0.12, "marker_size": 0.09,
    "dictionary": "DICT_4X4_50", "black_albedo_srgb8": [25, 25, 25],
    "patches": [{"name": "red", "corners": [0.03, 0.5, 0.21, 0.68], "albedo_linear": [0.6, 0.05, 0.04]}]}})";
  const CharucoSpec spec = ReadCharucoSpec(path);
  EXPECT_EQ(spec.squares_x, 6);
  ASSERT_EQ(spec.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(spec.patches[0].max_in_board.y(), 0.68);
  EXPECT_NEAR(spec.black_albedo.x(), SrgbToLinear(25 / 255.0), 1e-12);
  for (const char* bad : {R"({"charuco": {"squares": [6, 4], "square_size": 0.12, "marker_size": 0.15, "black_albedo_srgb8": [25, 25, 25]}})",
                          R"({"charuco": {"squares": [6, 4], "square_size": 0.12, "marker_size": 0.09, "dictionary": "DICT_9X9", "black_albedo_srgb8": [25, 25, 25]}})",
                          R"({"charuco": {"squares": [6, 4], "square_size": 0.12, "marker_size": 0.09, "black_albedo_srgb8": [25, 25, 25],
                              "patches": [{"corners": [0.2, 0.5, 0.1, 0.68], "albedo_srgb8": [1, 2, 3]}]}})"}) {
    std::ofstream(path) << bad;
    EXPECT_THROW(ReadCharucoSpec(path), std::runtime_error) << bad;
  }
}

// Found reviewing the reader for fuzz/board_fuzzer: 65536 x 65536 squares overflowed the marker count (undefined
// behaviour).
TEST(CharucoTarget, AHugeBoardIsAnErrorWithoutOverflow) {
  testing::TempDir dir;
  const auto path = dir.path() / "board.json";
  std::ofstream(path) << R"({"charuco": {"squares": [65536, 65536], "square_size": 0.12, "marker_size": 0.09,
    "black_albedo_srgb8": [25, 25, 25]}})";
  try {
    ReadCharucoSpec(path);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("fewer markers than the board's 2147483648"), std::string::npos)
        << error.what();
  }
}

TEST(CharucoTarget, FindsTheBoardAndCalibratesTheLutFromItsPatches) {
  testing::TempDir dir;
  const CharucoSpec spec = testing::PatchedCharucoSpec(0.12);
  const Mesh board = testing::CharucoBoardMesh(spec);
  const Camera camera = Camera::Pinhole(1, kWidth, kHeight, 500, 500);
  const CameraRays rays(camera);
  const Simulator simulator(board, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(),
                            SurfaceAlbedo::FromFaceColors(board));
  const Eigen::Vector3d centre(0.36, 0.24, 0.0);
  ObservationSet observations;
  std::uint64_t index = 0;
  int found = 0, frames = 0;
  double worst_rotation_deg = 0.0, worst_translation = 0.0, worst_known_albedo = 0.0;
  std::size_t known_pixels = 0;
  for (double distance : {0.9, 1.2, 1.5, 1.8, 2.1}) {
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.35, 0.25), Eigen::Vector2d(-0.35, 0.25),
                                         Eigen::Vector2d(0.35, -0.25), Eigen::Vector2d(-0.35, -0.25)}) {
      const double tilt = index % 2 ? 0.3 : -0.25;
      // OpenCV's board frame has z into the board: the printed side faces -z.
      const Eigen::Vector3d eye = centre + Eigen::Vector3d(offset.x() + distance * std::sin(tilt), offset.y(), -distance);
      const Rigid3d cam_from_world = CamFromWorldLookingAt(eye, (centre - eye).normalized(), Eigen::Vector3d(0, -1, 0));
      const cv::Mat image = testing::NoisySrgb8Frame(simulator, rays, cam_from_world, index++, 5, dir.path());
      ++frames;
      const std::optional<BoardView> view = FindCharuco(image, camera, spec);
      if (!view) continue;
      ++found;
      // Markers fix the board frame uniquely: it is the world frame here. The board's centre and its plane
      // (what shading and depth need), and below every known pixel on its patch or square (the rest).
      worst_translation = std::max(worst_translation,
                                   (view->cam_from_board * centre - cam_from_world * centre).norm() / distance);
      const Eigen::Vector3d expected_normal = cam_from_world.rotation * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d found_normal = view->cam_from_board.rotation * Eigen::Vector3d::UnitZ();
      worst_rotation_deg = std::max(worst_rotation_deg, std::acos(std::min(1.0, expected_normal.dot(found_normal))) * 180.0 / M_PI);
      const BoardMaps maps = RenderCharuco(spec, *view, rays);
      const cv::Mat truth = simulator.RenderAlbedo(rays, cam_from_world);
      for (int row = 0; row < kHeight; ++row) {
        for (int col = 0; col < kWidth; ++col) {
          const cv::Vec3f known = maps.known_albedo.at<cv::Vec3f>(row, col);
          if (std::isnan(known[0])) continue;
          ++known_pixels;
          const cv::Vec3f t = truth.at<cv::Vec3f>(row, col);
          for (int c = 0; c < 3; ++c) worst_known_albedo = std::max(worst_known_albedo, double(std::abs(known[c] - t[c])));
        }
      }
      for (const KnownColorObservation& observation : SampleKnownColors(image, maps.known_albedo, maps.maps, rays)) {
        observations.known_colors.push_back(observation);
      }
    }
  }
  std::printf("ChArUco board found in %d of %d frames; worst normal error %.3f deg, centre error %.4f of the "
              "distance; %zu known-colour pixels, worst difference to the rendered albedo %.4f (8-bit faces); "
              "%zu observations\n", found, frames, worst_rotation_deg, worst_translation, known_pixels,
              worst_known_albedo, observations.known_colors.size());
  EXPECT_GE(found, frames - 2);
  // 15 ChArUco corners of ~0.4 px noise (the renders are not anti-aliased) at up to 2.1 m fix the normal
  // less well than a chessboard's 54 (0.8 deg there); 2.4 deg changes cos_theta of a board tilted by 20
  // deg by about 1.5 %.
  EXPECT_LT(worst_rotation_deg, 3.0);
  EXPECT_LT(worst_translation, 0.01);
  EXPECT_LT(worst_known_albedo, 0.01);  // every known pixel lies on its patch or black square

  // Held out: a grey plane at 1.3 m, tilted, filling the view.
  const std::vector<double> errors = testing::HeldOutGreyPlaneErrors(
      observations, camera, 0.6, 2.4, Eigen::Vector3d(0, -0.4, 1.25), Eigen::Vector3d(0, 0.3, -0.95), dir.path());
  ASSERT_GT(errors.size(), static_cast<std::size_t>(kWidth * kHeight));
  std::printf("held-out grey plane restored from the ChArUco board's LUT: median error %.4f, p90 %.4f over %zu "
              "pixel-channels\n", errors[errors.size() / 2], errors[errors.size() * 9 / 10], errors.size());
  EXPECT_LT(errors[errors.size() / 2], 0.03);
}

}  // namespace
}  // namespace lutex
