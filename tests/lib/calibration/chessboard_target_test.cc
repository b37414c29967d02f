// A black-and-white chessboard as the only calibration target (paper Sec. 4.3), on frames the simulator
// rendered (8-bit sRGB, noisy; clear water, two spot lights 0.3 m to the sides): OpenCV finds the board
// and its pose matches the truth; the LUT calibrated from its squares alone restores a held-out grey
// board.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/chessboard_target.h"
#include "lib/calibration/known_color_sampling.h"
#include "lib/geometry/look_at.h"
#include "lib/image/image_io.h"
#include "lib/model/simulator.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

constexpr int kWidth = 640, kHeight = 480;
constexpr int kCornersX = 9, kCornersY = 6;
constexpr double kSquare = 0.08;
const Eigen::Matrix<std::uint8_t, 3, 1> kBlack(25, 25, 25), kWhite(225, 225, 225);

// The board in the plane z = 0 of the world: (kCornersX + 1) x (kCornersY + 1) squares, the first inner
// corner at the origin, squares from -kSquare; square (0, 0) (touching the origin from +x, +y) white; a
// white margin one square wide around it, as printed boards have.
Mesh ChessboardMesh() {
  Mesh mesh;
  for (int b = -2; b <= kCornersY; ++b) {
    for (int a = -2; a <= kCornersX; ++a) {
      const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
      const double x = a * kSquare, y = b * kSquare;
      mesh.vertices.insert(mesh.vertices.end(), {Eigen::Vector3d(x, y, 0), Eigen::Vector3d(x + kSquare, y, 0),
                                                 Eigen::Vector3d(x + kSquare, y + kSquare, 0),
                                                 Eigen::Vector3d(x, y + kSquare, 0)});
      mesh.faces.push_back({base, base + 1, base + 2});
      mesh.faces.push_back({base, base + 2, base + 3});
      const bool margin = a == -2 || b == -2 || a == kCornersX || b == kCornersY;
      const bool white = margin || ((a + b) % 2 + 2) % 2 == 0;
      mesh.face_colors.push_back(white ? kWhite : kBlack);
      mesh.face_colors.push_back(white ? kWhite : kBlack);
    }
  }
  return mesh;
}

ChessboardSpec Spec() {
  ChessboardSpec spec;
  spec.inner_corners_x = kCornersX;
  spec.inner_corners_y = kCornersY;
  spec.square_size = kSquare;
  spec.black_albedo = Eigen::Vector3d::Constant(SrgbToLinear(25 / 255.0));
  spec.white_albedo = Eigen::Vector3d::Constant(SrgbToLinear(225 / 255.0));
  return spec;
}

// A camera `distance` in front of the board's centre shifted by `offset` (metres, in the board plane),
// looking at the board's centre, so that the board lands off the image centre; tilted by looking from
// the side.
Rigid3d View(double distance, const Eigen::Vector2d& offset, double tilt) {
  const Eigen::Vector3d centre(0.5 * (kCornersX - 1) * kSquare, 0.5 * (kCornersY - 1) * kSquare, 0);
  const Eigen::Vector3d eye = centre + Eigen::Vector3d(offset.x() + distance * std::sin(tilt), offset.y(), distance);
  return CamFromWorldLookingAt(eye, (centre - eye).normalized() + Eigen::Vector3d(-offset.x(), -offset.y(), 0) / distance,
                               Eigen::Vector3d(0, -1, 0));
}

TEST(ChessboardTarget, ReadsTheFileAndRejectsNonsense) {
  testing::TempDir dir;
  const auto path = dir.path() / "board.json";
  std::ofstream(path) << R"({"chessboard": {"inner_corners": [9, 6], "square_size": 0.08,
    "black_albedo_srgb8": [25, 25, 25], "white_albedo_linear": [0.75, 0.75, 0.75]}})";
  const ChessboardSpec spec = ReadChessboardSpec(path);
  EXPECT_EQ(spec.inner_corners_x, 9);
  EXPECT_NEAR(spec.black_albedo.x(), SrgbToLinear(25 / 255.0), 1e-12);
  EXPECT_DOUBLE_EQ(spec.white_albedo.y(), 0.75);
  std::ofstream(path) << R"({"chessboard": {"inner_corners": [9, 6], "square_size": 0.08,
    "black_albedo_srgb8": [225, 225, 225], "white_albedo_srgb8": [25, 25, 25]}})";
  EXPECT_THROW(ReadChessboardSpec(path), std::runtime_error);
  std::ofstream(path) << R"({"chessboard": {"inner_corners": [9], "square_size": 0.08}})";
  EXPECT_THROW(ReadChessboardSpec(path), std::runtime_error);
}

// The message ReadChessboardSpec throws for a board file of `text`, or "no error".
std::string ChessboardSpecError(const std::string& text) {
  testing::TempDir dir;
  const auto path = dir.path() / "board.json";
  std::ofstream(path) << text;
  try {
    ReadChessboardSpec(path);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "no error";
}

// Found reviewing the reader for fuzz/board_fuzzer: a corrupt corner count of 600000 passed to OpenCV's search.
TEST(ChessboardTarget, AnImplausibleCornerCountIsAnError) {
  const std::string error = ChessboardSpecError(R"({"chessboard": {"inner_corners": [9, 600000], "square_size": 0.08,
    "black_albedo_srgb8": [25, 25, 25], "white_albedo_linear": [0.75, 0.75, 0.75]}})");
  EXPECT_NE(error.find("more than 1000 inner corners"), std::string::npos) << error;
}

// Found by fuzz/board_fuzzer: a corner count of 6e73 was cast to int by the JSON library (undefined behaviour).
TEST(ChessboardTarget, ACornerCountBeyondIntIsAnError) {
  const std::string error = ChessboardSpecError(R"({"chessboard": {"inner_corners": [9, 6e73], "square_size": 0.08,
    "black_albedo_srgb8": [25, 25, 25], "white_albedo_linear": [0.75, 0.75, 0.75]}})");
  EXPECT_NE(error.find("inner_corners must be a whole number from 0 to 2147483647"), std::string::npos) << error;
}

TEST(ChessboardTarget, FindsTheBoardAndCalibratesTheLutFromItsSquaresAlone) {
  testing::TempDir dir;
  const Mesh board = ChessboardMesh();
  const Camera camera = Camera::Pinhole(1, kWidth, kHeight, 500, 500);
  const CameraRays rays(camera);
  const ChessboardSpec spec = Spec();
  const Simulator simulator(board, testing::TwoCosineLights(0.3, 1.0, 1.5), testing::ClearWater(),
                            SurfaceAlbedo::FromFaceColors(board));
  ObservationSet observations;
  std::uint64_t index = 0;
  double worst_rotation_deg = 0.0, worst_translation = 0.0;
  int found = 0, frames = 0;
  for (double distance : {1.0, 1.3, 1.7, 2.1, 2.6}) {
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.35, 0.25), Eigen::Vector2d(-0.35, 0.25),
                                         Eigen::Vector2d(0.35, -0.25), Eigen::Vector2d(-0.35, -0.25)}) {
      const double tilt = index % 2 ? 0.3 : -0.2;
      const Rigid3d cam_from_world = View(distance, offset * distance / 1.3, tilt);
      const cv::Mat image = testing::NoisySrgb8Frame(simulator, rays, cam_from_world, index++, 9, dir.path());
      ++frames;
      const std::optional<BoardView> view = FindChessboard(image, camera, spec);
      if (!view) continue;
      ++found;
      // The board frame is the world frame here, up to OpenCV's choice of the first corner (a symmetry of
      // the pattern): compare the board's plane and centre, which do not depend on it.
      const Eigen::Vector3d centre_in_board(0.5 * (kCornersX - 1) * kSquare, 0.5 * (kCornersY - 1) * kSquare, 0);
      const Eigen::Vector3d expected_centre = cam_from_world * centre_in_board;
      const Rigid3d& found_pose = view->cam_from_board;
      worst_translation = std::max(worst_translation, (found_pose * centre_in_board - expected_centre).norm() / distance);
      const Eigen::Vector3d expected_normal = cam_from_world.rotation * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d found_normal = found_pose.rotation * Eigen::Vector3d::UnitZ();
      worst_rotation_deg = std::max(worst_rotation_deg,
                                    std::acos(std::min(1.0, std::abs(expected_normal.dot(found_normal)))) * 180.0 / M_PI);
      EXPECT_LT(view->reprojection_rms, 1.0);  // the renders are not anti-aliased: corners carry ~0.5 px noise
      const BoardMaps maps = RenderChessboard(spec, *view, rays, image);
      for (const KnownColorObservation& observation : SampleKnownColors(image, maps.known_albedo, maps.maps, rays)) {
        observations.known_colors.push_back(observation);
      }
    }
  }
  std::printf("chessboard found in %d of %d frames; worst normal error %.3f deg, centre error %.4f of the distance; "
              "%zu known-colour observations\n", found, frames, worst_rotation_deg, worst_translation,
              observations.known_colors.size());
  EXPECT_GE(found, frames - 3);
  EXPECT_LT(worst_rotation_deg, 1.5);
  EXPECT_LT(worst_translation, 0.01);

  // Held out: a grey plane at 1.8 m, tilted, filling the view.
  const std::vector<double> errors = testing::HeldOutGreyPlaneErrors(
      observations, camera, 0.8, 2.8, Eigen::Vector3d(0, -0.6, 1.7), Eigen::Vector3d(0, 0.33, -0.94), dir.path());
  ASSERT_GT(errors.size(), static_cast<std::size_t>(kWidth * kHeight));
  std::printf("held-out grey plane restored from the chessboard's LUT: median error %.4f, p90 %.4f over %zu "
              "pixel-channels\n", errors[errors.size() / 2], errors[errors.size() * 9 / 10], errors.size());
  EXPECT_LT(errors[errors.size() / 2], 0.03);
}

}  // namespace
}  // namespace lutex
