#include "lib/calibration/chessboard_target.h"

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

#include "lib/image/image_io.h"

namespace lutex {

namespace {

Eigen::Vector3d ReadAlbedo(const nlohmann::json& board, const std::string& colour) {
  if (board.contains(colour + "_albedo_linear")) {
    const auto values = board.at(colour + "_albedo_linear").get<std::vector<double>>();
    if (values.size() != 3) throw std::runtime_error(colour + "_albedo_linear must have 3 values");
    return Eigen::Vector3d(values[0], values[1], values[2]);
  }
  const auto values = board.at(colour + "_albedo_srgb8").get<std::vector<double>>();
  if (values.size() != 3) throw std::runtime_error(colour + "_albedo_srgb8 must have 3 values");
  Eigen::Vector3d albedo;
  for (int c = 0; c < 3; ++c) {
    if (!(values[c] >= 0.0 && values[c] <= 255.0)) throw std::runtime_error(colour + "_albedo_srgb8 must be in [0, 255]");
    albedo[c] = SrgbToLinear(values[c] / 255.0);
  }
  return albedo;
}

}  // namespace

void ChessboardSpec::Check() const {
  if (inner_corners_x < 3 || inner_corners_y < 3) {
    throw std::invalid_argument("a chessboard needs at least 3 x 3 inner corners");
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
    const auto corners = board.at("inner_corners").get<std::vector<int>>();
    if (corners.size() != 2) throw std::runtime_error("inner_corners must be [across, down]");
    spec.inner_corners_x = corners[0];
    spec.inner_corners_y = corners[1];
    spec.square_size = board.at("square_size").get<double>();
    spec.black_albedo = ReadAlbedo(board, "black");
    spec.white_albedo = ReadAlbedo(board, "white");
    spec.Check();
  } catch (const std::exception& error) {
    throw std::runtime_error(path.string() + ": " + error.what());
  }
  return spec;
}

std::optional<ChessboardView> FindChessboard(const cv::Mat& linear_rgb, const Camera& camera,
                                             const ChessboardSpec& spec) {
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
  // OpenCV's pixel centres are integers; COLMAP's (the camera's) are at +0.5. Undistorted, normalised.
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> normalised;
  std::vector<Eigen::Vector2d> detected;
  for (int j = 0; j < spec.inner_corners_y; ++j) {
    for (int i = 0; i < spec.inner_corners_x; ++i) {
      const cv::Point2f& corner = corners[static_cast<std::size_t>(j * spec.inner_corners_x + i)];
      const Eigen::Vector2d pixel(corner.x + 0.5, corner.y + 0.5);
      const Eigen::Vector3d ray = camera.CamFromImg(pixel);
      object.emplace_back(i * spec.square_size, j * spec.square_size, 0.0);
      normalised.emplace_back(ray.x() / ray.z(), ray.y() / ray.z());
      detected.push_back(pixel);
    }
  }
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, normalised, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    return std::nullopt;
  }
  cv::Mat rotation;
  cv::Rodrigues(rvec, rotation);
  Eigen::Matrix3d cam_from_board_rotation;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) cam_from_board_rotation(r, c) = rotation.at<double>(r, c);
  }
  ChessboardView view;
  view.cam_from_board = Rigid3d(Eigen::Quaterniond(cam_from_board_rotation).normalized(),
                                Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
  double squared = 0.0;
  for (std::size_t k = 0; k < object.size(); ++k) {
    const Eigen::Vector3d point_in_cam = view.cam_from_board * Eigen::Vector3d(object[k].x, object[k].y, object[k].z);
    squared += (camera.ImgFromCam(point_in_cam) - detected[k]).squaredNorm();
  }
  view.reprojection_rms = std::sqrt(squared / static_cast<double>(object.size()));
  return view;
}

ChessboardMaps RenderChessboard(const ChessboardSpec& spec, const ChessboardView& view, const CameraRays& rays,
                                const cv::Mat& linear_rgb) {
  const int width = rays.width(), height = rays.height();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ChessboardMaps result;
  result.maps.depth = cv::Mat(height, width, CV_32F, cv::Scalar(nan));
  result.maps.normal = cv::Mat(height, width, CV_32FC3, cv::Scalar::all(nan));
  result.known_albedo = cv::Mat(height, width, CV_32FC3, cv::Scalar::all(nan));
  cv::Mat parity(height, width, CV_8S, cv::Scalar(-1));  // 0 or 1 on the inner part of a square

  const Eigen::Matrix3d board_from_cam_rotation = view.cam_from_board.rotation.conjugate().toRotationMatrix();
  const Eigen::Vector3d normal_in_cam = view.cam_from_board.rotation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d origin_in_cam = view.cam_from_board.translation;
  const double s = spec.square_size;
  const double half_inner = 0.5 * spec.inner_fraction;
  double parity_sum[2] = {0.0, 0.0};
  int parity_count[2] = {0, 0};
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      const double along = normal_in_cam.dot(direction);
      if (!std::isfinite(along) || std::abs(along) < 1e-9) continue;
      const double range = normal_in_cam.dot(origin_in_cam) / along;
      if (!(range > 0.0)) continue;
      const Eigen::Vector3d point_in_cam = range * direction;
      const Eigen::Vector3d point_in_board = board_from_cam_rotation * (point_in_cam - origin_in_cam);
      const double x = point_in_board.x() / s, y = point_in_board.y() / s;
      if (x < -1.0 || y < -1.0 || x > spec.inner_corners_x || y > spec.inner_corners_y) continue;
      result.maps.depth.at<float>(row, col) = static_cast<float>(point_in_cam.z());
      const Eigen::Vector3d facing = along < 0.0 ? normal_in_cam : Eigen::Vector3d(-normal_in_cam);
      result.maps.normal.at<cv::Vec3f>(row, col) = cv::Vec3f(float(facing.x()), float(facing.y()), float(facing.z()));
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
