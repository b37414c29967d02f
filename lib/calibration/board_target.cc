#include "lib/calibration/board_target.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>

#include <Eigen/Geometry>

namespace lutex {

namespace {

// solvePnP (IPPE) on undistorted, normalised points; nothing when it fails.
std::optional<Rigid3d> SolvePlanarPose(const std::vector<Eigen::Vector3d>& points_in_board,
                                       const std::vector<Eigen::Vector2d>& pixels, const Camera& camera) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> normalised;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const Eigen::Vector3d ray = camera.CamFromImg(pixels[k]);
    object.emplace_back(points_in_board[k].x(), points_in_board[k].y(), points_in_board[k].z());
    normalised.emplace_back(ray.x() / ray.z(), ray.y() / ray.z());
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
  return Rigid3d(Eigen::Quaterniond(cam_from_board_rotation).normalized(),
                 Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
}

std::vector<double> ReprojectionErrors(const Rigid3d& cam_from_board, const std::vector<Eigen::Vector3d>& points_in_board,
                                       const std::vector<Eigen::Vector2d>& pixels, const Camera& camera) {
  std::vector<double> errors;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    errors.push_back((camera.ImgFromCam(cam_from_board * points_in_board[k]) - pixels[k]).norm());
  }
  return errors;
}

}  // namespace

std::optional<BoardView> PoseFromBoardPoints(const std::vector<Eigen::Vector3d>& points_in_board,
                                             const std::vector<Eigen::Vector2d>& pixels, const Camera& camera) {
  if (points_in_board.size() != pixels.size() || points_in_board.size() < 4) return std::nullopt;
  std::optional<Rigid3d> pose = SolvePlanarPose(points_in_board, pixels, camera);
  if (!pose) return std::nullopt;
  // One pass against outliers (a corner OpenCV placed wrongly): points off by more than 3 x the median
  // and 1 px are dropped and the pose solved again.
  std::vector<double> errors = ReprojectionErrors(*pose, points_in_board, pixels, camera);
  std::vector<double> sorted = errors;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double limit = std::max(1.0, 3.0 * sorted[sorted.size() / 2]);
  std::vector<Eigen::Vector3d> kept_points;
  std::vector<Eigen::Vector2d> kept_pixels;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    if (errors[k] > limit) continue;
    kept_points.push_back(points_in_board[k]);
    kept_pixels.push_back(pixels[k]);
  }
  if (kept_points.size() < pixels.size() && kept_points.size() >= 4) {
    pose = SolvePlanarPose(kept_points, kept_pixels, camera);
    if (!pose) return std::nullopt;
    errors = ReprojectionErrors(*pose, kept_points, kept_pixels, camera);
  }
  BoardView view;
  view.cam_from_board = *pose;
  double squared = 0.0;
  for (const double error : errors) squared += error * error;
  view.reprojection_rms = std::sqrt(squared / static_cast<double>(errors.size()));
  return view;
}

BoardPlaneMaps RenderBoardPlane(const BoardView& view, const CameraRays& rays, const Eigen::Vector2d& min_in_board,
                                const Eigen::Vector2d& max_in_board) {
  const int width = rays.width(), height = rays.height();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  BoardPlaneMaps result;
  result.maps.depth = cv::Mat(height, width, CV_32F, cv::Scalar(nan));
  result.maps.normal = cv::Mat(height, width, CV_32FC3, cv::Scalar::all(nan));
  result.point_in_board = cv::Mat(height, width, CV_32FC2, cv::Scalar::all(nan));
  const Eigen::Matrix3d board_from_cam_rotation = view.cam_from_board.rotation.conjugate().toRotationMatrix();
  const Eigen::Vector3d normal_in_cam = view.cam_from_board.rotation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d origin_in_cam = view.cam_from_board.translation;
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      const double along = normal_in_cam.dot(direction);
      if (!std::isfinite(along) || std::abs(along) < 1e-9) continue;
      const double range = normal_in_cam.dot(origin_in_cam) / along;
      if (!(range > 0.0)) continue;
      const Eigen::Vector3d point_in_cam = range * direction;
      const Eigen::Vector3d point_in_board = board_from_cam_rotation * (point_in_cam - origin_in_cam);
      if (point_in_board.x() < min_in_board.x() || point_in_board.y() < min_in_board.y() ||
          point_in_board.x() > max_in_board.x() || point_in_board.y() > max_in_board.y()) {
        continue;
      }
      result.maps.depth.at<float>(row, col) = static_cast<float>(point_in_cam.z());
      const Eigen::Vector3d facing = along < 0.0 ? normal_in_cam : Eigen::Vector3d(-normal_in_cam);
      result.maps.normal.at<cv::Vec3f>(row, col) = cv::Vec3f(float(facing.x()), float(facing.y()), float(facing.z()));
      result.point_in_board.at<cv::Vec2f>(row, col) = cv::Vec2f(float(point_in_board.x()), float(point_in_board.y()));
    }
  }
  return result;
}

}  // namespace lutex
