#pragma once

// A black-and-white chessboard of known albedo as a calibration target (paper Sec. 4.3): OpenCV finds its
// inner corners (findChessboardCornersSB), the board's pose comes from solvePnP with the camera's
// intrinsics, and the centres of its black and white squares become known-colour pixels. No COLMAP model
// and no mesh are needed for the calibration images, only the camera.
//
// The chessboard file (JSON):
//   {"chessboard": {"inner_corners": [9, 6], "square_size": 0.1,
//                   "black_albedo_srgb8": [30, 30, 30], "white_albedo_srgb8": [230, 230, 230]}}
// ("black_albedo_linear" / "white_albedo_linear" in [0, 1] instead, when known linearly). inner_corners
// are the corners where four squares meet, across and down (squares minus one); square_size in metres.
// Which squares are black is read from the image (the darker of the two square parities), so the board's
// orientation in the image does not matter.

#include <filesystem>
#include <optional>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/calibration/board_target.h"

namespace lutex {

struct ChessboardSpec {
  int inner_corners_x = 0;
  int inner_corners_y = 0;
  double square_size = 0.0;                              // metres
  Eigen::Vector3d black_albedo = Eigen::Vector3d::Zero();  // linear
  Eigen::Vector3d white_albedo = Eigen::Vector3d::Zero();
  // Fraction of a square's side kept around its centre for known-colour pixels (edges blur and mix).
  double inner_fraction = 0.6;

  // Throws std::invalid_argument on a board OpenCV cannot find (fewer than 3 x 3 inner corners), a
  // non-positive square size, albedo out of [0, 1], or black not darker than white.
  void Check() const;
};

// Throws std::runtime_error naming the file and the key on anything malformed.
ChessboardSpec ReadChessboardSpec(const std::filesystem::path& path);

// The board in a linear RGB image (CV_32FC3) of `camera`, or nothing when OpenCV does not find all inner
// corners. Board frame (board_target.h): origin at the first inner corner OpenCV reports, x along its
// rows, y down its columns. Distorted camera models are handled (PoseFromBoardPoints).
std::optional<BoardView> FindChessboard(const cv::Mat& linear_rgb, const Camera& camera, const ChessboardSpec& spec);

// The board's maps in a view (BoardMaps): known albedo on the inner part of every square. `linear_rgb`
// decides which square parity is black.
BoardMaps RenderChessboard(const ChessboardSpec& spec, const BoardView& view, const CameraRays& rays,
                                const cv::Mat& linear_rgb);

}  // namespace lutex
