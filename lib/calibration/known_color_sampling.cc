#include "lib/calibration/known_color_sampling.h"

#include <cmath>
#include <stdexcept>

#include "lib/model/image_formation.h"

namespace lutex {

void KnownColorSamplingOptions::Check() const {
  if (stride < 1 || edge_margin < 0) throw std::invalid_argument("sampling needs stride >= 1 and edge_margin >= 0");
  if (!(min_cos_theta > 0.0 && min_cos_theta < 1.0)) throw std::invalid_argument("min_cos_theta must be in (0, 1)");
}

std::vector<KnownColorObservation> SampleKnownColors(const cv::Mat& image, const cv::Mat& known_albedo,
                                                     const GeometryMaps& maps, const CameraRays& rays,
                                                     const KnownColorSamplingOptions& options) {
  options.Check();
  CV_Assert(image.type() == CV_32FC3 && known_albedo.type() == CV_32FC3 && image.size() == known_albedo.size());
  std::vector<KnownColorObservation> observations;
  const int margin = options.edge_margin;
  for (int row = margin; row + margin < image.rows; row += options.stride) {
    for (int col = margin; col + margin < image.cols; col += options.stride) {
      const cv::Vec3f albedo = known_albedo.at<cv::Vec3f>(row, col);
      const float depth = maps.depth.at<float>(row, col);
      if (std::isnan(albedo[0]) || std::isnan(depth)) continue;
      bool homogeneous = true;
      for (int dr = -margin; dr <= margin && homogeneous; ++dr) {
        for (int dc = -margin; dc <= margin && homogeneous; ++dc) {
          const float neighbour_depth = maps.depth.at<float>(row + dr, col + dc);
          homogeneous = known_albedo.at<cv::Vec3f>(row + dr, col + dc) == albedo &&
                        std::abs(neighbour_depth - depth) <= options.max_relative_depth_step * depth;
        }
      }
      if (!homogeneous) continue;
      const cv::Vec3f value = image.at<cv::Vec3f>(row, col);
      if (std::max({value[0], value[1], value[2]}) >= options.saturation_level) continue;
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      KnownColorObservation observation;
      observation.pixel = Eigen::Vector2d(col + 0.5, row + 0.5);
      observation.point_in_cam = (depth / direction.z()) * direction;
      const cv::Vec3f normal = maps.normal.at<cv::Vec3f>(row, col);
      observation.normal_in_cam = Eigen::Vector3d(normal[0], normal[1], normal[2]);
      observation.cos_theta = options.shading.Cosine(observation.point_in_cam, observation.normal_in_cam);
      if (observation.cos_theta < options.min_cos_theta) continue;
      observation.intensity = Eigen::Vector3d(value[0], value[1], value[2]);
      observation.albedo = Eigen::Vector3d(albedo[0], albedo[1], albedo[2]);
      observations.push_back(observation);
    }
  }
  return observations;
}

}  // namespace lutex
