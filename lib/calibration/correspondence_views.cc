#include "lib/calibration/correspondence_views.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "lib/model/image_formation.h"
#include "lib/util/median.h"

namespace lutex {

void CorrespondenceViewOptions::Check() const {
  if (!(max_relative_depth_difference > 0.0) || !(max_relative_color_spread > 0.0) || max_footprint_pixels < 1) {
    throw std::invalid_argument("correspondence tolerances must be positive");
  }
  if (!(min_cos_theta > 0.0 && min_cos_theta < 1.0)) throw std::invalid_argument("min_cos_theta must be in (0, 1)");
}

std::optional<SurfaceView> ViewInOtherImage(const Eigen::Vector3d& point_in_world, double footprint_radius_world,
                                            const ViewedImage& other, const CorrespondenceViewOptions& options) {
  const Eigen::Vector3d point_in_cam = other.cam_from_world * point_in_world;
  if (!(point_in_cam.z() > 0.0)) return std::nullopt;
  const Camera& camera = other.rays.camera();
  const Eigen::Vector2d pixel = camera.ImgFromCam(point_in_cam);
  const double radius = std::max(1.0, footprint_radius_world * camera.FocalLengthX() / point_in_cam.z());
  const int col = static_cast<int>(std::floor(pixel.x())), row = static_cast<int>(std::floor(pixel.y()));
  const int reach = static_cast<int>(std::ceil(radius));
  if (!pixel.allFinite() || col - reach < 0 || row - reach < 0 || col + reach >= other.image.cols ||
      row + reach >= other.image.rows) {
    return std::nullopt;
  }
  // Depth test at the pixel: the surface this image shows there is the point's own.
  const double tolerance = options.max_relative_depth_difference * point_in_cam.z();
  const float depth = other.maps.depth.at<float>(row, col);
  if (std::isnan(depth) || std::abs(depth - point_in_cam.z()) > tolerance) return std::nullopt;
  const cv::Vec3f normal = other.maps.normal.at<cv::Vec3f>(row, col);
  SurfaceView view;
  const Eigen::Vector3d direction = other.rays.Direction(col, row).cast<double>();
  view.pixel = Eigen::Vector2d(col + 0.5, row + 0.5);
  view.point_in_cam = (depth / direction.z()) * direction;
  view.normal_in_cam = Eigen::Vector3d(normal[0], normal[1], normal[2]);
  view.cos_theta = options.shading.Cosine(view.point_in_cam, view.normal_in_cam);
  if (view.cos_theta < options.min_cos_theta) return std::nullopt;

  // The footprint: one surface (within the depth tolerance plus the tilt across it) of one colour.
  const int disk_pixels = static_cast<int>(M_PI * radius * radius) + 1;
  const int step = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(disk_pixels) / options.max_footprint_pixels)));
  const double depth_spread = tolerance + radius / camera.FocalLengthX() * depth / std::max(view.cos_theta, 0.3);
  std::vector<float> channels[3];
  for (int dr = -reach; dr <= reach; dr += step) {
    for (int dc = -reach; dc <= reach; dc += step) {
      if (dr * dr + dc * dc > radius * radius) continue;
      const float here = other.maps.depth.at<float>(row + dr, col + dc);
      if (std::isnan(here) || std::abs(here - depth) > depth_spread) return std::nullopt;
      const cv::Vec3f value = other.image.at<cv::Vec3f>(row + dr, col + dc);
      if (std::max({value[0], value[1], value[2]}) >= options.saturation_level) return std::nullopt;
      for (int c = 0; c < 3; ++c) channels[c].push_back(value[c]);
    }
  }
  for (int c = 0; c < 3; ++c) view.intensity[c] = MedianInPlace(channels[c]);
  if (!(view.intensity.y() > 0.0) ||
      MedianAbsoluteDeviation(channels[1], view.intensity.y()) > options.max_relative_color_spread * view.intensity.y()) {
    return std::nullopt;
  }
  return view;
}

}  // namespace lutex
