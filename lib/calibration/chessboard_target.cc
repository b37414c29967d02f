#include "lib/calibration/chessboard_target.h"

#include <climits>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Geometry>

#include "lib/calibration/albedo_json.h"
#include "lib/image/image_io.h"
#include "lib/util/json_fields.h"

namespace lutex {

void ChessboardSpec::Check() const {
  if (inner_corners_x < 3 || inner_corners_y < 3) {
    throw std::invalid_argument("a chessboard needs at least 3 x 3 inner corners");
  }
  if (inner_corners_x > 1000 || inner_corners_y > 1000) {  // a corrupt count, not a board OpenCV could find
    throw std::invalid_argument("a chessboard of more than 1000 inner corners a side is implausible (a typo?)");
  }
  if (!(square_size > 0.0)) throw std::invalid_argument("the chessboard's square_size must be positive");
  for (const Eigen::Vector3d* albedo : {&black_albedo, &white_albedo}) {
    if (!(albedo->minCoeff() >= 0.0 && albedo->maxCoeff() <= 1.0)) {
      throw std::invalid_argument("chessboard albedo must be in [0, 1]");
    }
  }
  if (!(black_albedo.y() < white_albedo.y())) throw std::invalid_argument("the black squares must be darker than the white");
  if (!(inner_fraction > 0.0 && inner_fraction <= 1.0)) throw std::invalid_argument("inner_fraction must be in (0, 1]");
}

ChessboardSpec ReadChessboardSpec(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path.string() + ": cannot read the chessboard file");
  ChessboardSpec spec;
  try {
    const nlohmann::json json = nlohmann::json::parse(file);
    const nlohmann::json& board = json.at("chessboard");
    const nlohmann::json& corners = board.at("inner_corners");
    if (!corners.is_array() || corners.size() != 2) throw std::runtime_error("inner_corners must be [across, down]");
    spec.inner_corners_x = static_cast<int>(WholeNumber(corners[0], "inner_corners", 0, INT_MAX));
    spec.inner_corners_y = static_cast<int>(WholeNumber(corners[1], "inner_corners", 0, INT_MAX));
    spec.square_size = board.at("square_size").get<double>();
    spec.black_albedo = ReadAlbedo(board, "black_albedo");
    spec.white_albedo = ReadAlbedo(board, "white_albedo");
    spec.Check();
  } catch (const std::exception& error) {
    throw std::runtime_error(path.string() + ": " + JsonErrorText(error));
  }
  return spec;
}

std::optional<BoardView> FindChessboard(const cv::Mat& linear_rgb, const Camera& camera, const ChessboardSpec& spec) {
  spec.Check();
  cv::Mat grey;
  cv::cvtColor(EncodeLinearImage(linear_rgb, ImageEncoding::kSrgb8), grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(spec.inner_corners_x, spec.inner_corners_y);
  // The plain search first: on small squares (8-15 px) the exhaustive and high-accuracy modes miss boards
  // that it finds (simulated 320 x 240 frames: 20 of 20 against 7); the exhaustive one as the fallback.
  bool found = false;
  for (const int flags : {0, cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE}) {
    if ((found = cv::findChessboardCornersSB(grey, pattern, corners, flags))) break;
  }
  if (!found) return std::nullopt;
  std::vector<Eigen::Vector3d> points_in_board;
  std::vector<Eigen::Vector2d> pixels;
  for (int j = 0; j < spec.inner_corners_y; ++j) {
    for (int i = 0; i < spec.inner_corners_x; ++i) {
      const cv::Point2f& corner = corners[static_cast<std::size_t>(j * spec.inner_corners_x + i)];
      points_in_board.emplace_back(i * spec.square_size, j * spec.square_size, 0.0);
      pixels.emplace_back(corner.x + 0.5, corner.y + 0.5);  // OpenCV's pixel centres are integers
    }
  }
  return PoseFromBoardPoints(points_in_board, pixels, camera);
}

BoardMaps RenderChessboard(const ChessboardSpec& spec, const BoardView& view, const CameraRays& rays,
                                const cv::Mat& linear_rgb) {
  const double s = spec.square_size;
  BoardPlaneMaps plane = RenderBoardPlane(view, rays, Eigen::Vector2d(-s, -s),
                                          Eigen::Vector2d(spec.inner_corners_x * s, spec.inner_corners_y * s));
  const int width = rays.width(), height = rays.height();
  BoardMaps result;
  result.maps = std::move(plane.maps);
  result.known_albedo = cv::Mat(height, width, CV_32FC3, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
  cv::Mat parity(height, width, CV_8S, cv::Scalar(-1));  // 0 or 1 on the inner part of a square
  const double half_inner = 0.5 * spec.inner_fraction;
  double parity_sum[2] = {0.0, 0.0};
  int parity_count[2] = {0, 0};
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const cv::Vec2f point = plane.point_in_board.at<cv::Vec2f>(row, col);
      if (std::isnan(point[0])) continue;
      const double x = point[0] / s, y = point[1] / s;
      const double square_x = std::floor(x), square_y = std::floor(y);
      if (std::abs(x - square_x - 0.5) > half_inner || std::abs(y - square_y - 0.5) > half_inner) continue;
      const int p = static_cast<int>(std::fmod(std::fmod(square_x + square_y, 2.0) + 2.0, 2.0));
      parity.at<std::int8_t>(row, col) = static_cast<std::int8_t>(p);
      parity_sum[p] += linear_rgb.at<cv::Vec3f>(row, col)[1];
      ++parity_count[p];
    }
  }
  // The darker parity is black.
  const int black = parity_count[0] && parity_count[1] &&
                            parity_sum[0] / parity_count[0] > parity_sum[1] / parity_count[1] ? 1 : 0;
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const int p = parity.at<std::int8_t>(row, col);
      if (p < 0) continue;
      const Eigen::Vector3d& albedo = p == black ? spec.black_albedo : spec.white_albedo;
      result.known_albedo.at<cv::Vec3f>(row, col) = cv::Vec3f(float(albedo.x()), float(albedo.y()), float(albedo.z()));
    }
  }
  return result;
}

}  // namespace lutex
