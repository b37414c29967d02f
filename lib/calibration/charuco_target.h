#pragma once

// A ChArUco board with coloured patches as a calibration target (issue: known-colour targets, way (c)):
// ArUco markers in the white squares of a chessboard make the board found and posed even when it is
// partly out of view or occluded, and the patches around it (printed colours of known albedo) become
// known-colour pixels, with the black squares. No COLMAP model and no mesh are needed, only the camera.
//
// The board file (JSON):
//   {"charuco": {"squares": [7, 5], "square_size": 0.1, "marker_size": 0.075, "dictionary": "DICT_4X4_50",
//                "black_albedo_srgb8": [30, 30, 30],
//                "patches": [{"name": "red", "corners": [x0, y0, x1, y1], "albedo_srgb8": [200, 40, 40]}, ...]}}
// squares across and down, sizes in metres, dictionary one of OpenCV's predefined ArUco dictionaries
// (DICT_4X4_50 ... DICT_7X7_1000, DICT_ARUCO_ORIGINAL); albedo as "..._srgb8" or "..._linear". Patches are
// axis-aligned rectangles in the board frame, OpenCV's: origin at the top-left corner of the board as
// CharucoBoard::draw renders it, x to the right, y down, z into the board (the printed side faces -z);
// ChArUco corner id k at ((k mod (squares_x - 1)) + 1, (k div (squares_x - 1)) + 1) x square_size.
// Patches may lie on the board's margin or on squares. The white squares carry markers and give no known
// colour.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/calibration/board_target.h"

namespace lutex {

struct ColourPatch {
  std::string name;
  Eigen::Vector2d min_in_board = Eigen::Vector2d::Zero();  // metres
  Eigen::Vector2d max_in_board = Eigen::Vector2d::Zero();
  Eigen::Vector3d albedo = Eigen::Vector3d::Zero();  // linear
};

struct CharucoSpec {
  int squares_x = 0;
  int squares_y = 0;
  double square_size = 0.0;  // metres
  double marker_size = 0.0;  // metres, < square_size
  std::string dictionary = "DICT_4X4_50";
  Eigen::Vector3d black_albedo = Eigen::Vector3d::Zero();  // linear
  std::vector<ColourPatch> patches;
  // Fraction of a square's or patch's sides kept around its centre for known-colour pixels.
  double inner_fraction = 0.6;
  // Fewest ChArUco corners for a pose.
  int min_corners = 6;

  // Throws std::invalid_argument naming the problem (too few squares, sizes, unknown dictionary, more
  // markers than the dictionary has, albedo out of [0, 1], empty patches).
  void Check() const;
};

// Throws std::runtime_error naming the file and the key on anything malformed.
CharucoSpec ReadCharucoSpec(const std::filesystem::path& path);

// The board in a linear RGB image (CV_32FC3) of `camera`: markers found, ChArUco corners interpolated,
// pose from them (PoseFromBoardPoints); nothing when fewer than spec.min_corners corners are found.
std::optional<BoardView> FindCharuco(const cv::Mat& linear_rgb, const Camera& camera, const CharucoSpec& spec);

// The board's maps in a view (BoardMaps), over the board and its patches: known albedo on the inner part
// of every black square and patch.
BoardMaps RenderCharuco(const CharucoSpec& spec, const BoardView& view, const CameraRays& rays);

// Which squares are black (no marker), row-major, squares_x per row; square (i, j) spans
// [i, i + 1] x [j, j + 1] square sizes in the board frame. The markers' corners in the board frame
// (OpenCV's order: the marker image's top-left, top-right, bottom-right, bottom-left) and their ids.
struct CharucoLayout {
  std::vector<bool> black;
  std::vector<std::array<Eigen::Vector2d, 4>> marker_corners;
  std::vector<int> marker_ids;
};
CharucoLayout CharucoBoardLayout(const CharucoSpec& spec);

// The bits of marker `id` of the spec's dictionary with its black border: (bits + 2)^2 values, row-major
// over the marker image, true = white.
std::vector<bool> CharucoMarkerBits(const CharucoSpec& spec, int id, int* cells_per_side);

}  // namespace lutex
