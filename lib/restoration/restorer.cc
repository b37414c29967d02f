#include "lib/restoration/restorer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lutex {

void RestorationOptions::Check() const {
  if (!(model.min_cos_theta > 0.0 && model.min_cos_theta < 1.0)) throw std::invalid_argument("min_cos_theta must be in (0, 1)");
  if (!(saturation_level > 0.0)) throw std::invalid_argument("saturation_level must be positive");
  if (shot_noise < 0.0 || read_noise < 0.0 || !(signal_to_noise > 0.0)) {
    throw std::invalid_argument("noise model needs shot_noise, read_noise >= 0 and signal_to_noise > 0");
  }
}

RestoredImage RestoreImage(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays, const FrustumLut& lut,
                           const RestorationOptions& options, const FrustumLut* coverage) {
  options.Check();
  CV_Assert(image.type() == CV_32FC3 && !maps.normal.empty());
  if (image.cols != rays.width() || image.rows != rays.height()) {
    throw std::invalid_argument("image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                " but its camera is " + std::to_string(rays.width()) + "x" + std::to_string(rays.height()));
  }
  if (lut.grid().image_width != image.cols || lut.grid().image_height != image.rows) {
    throw std::invalid_argument("the LUT is for " + std::to_string(lut.grid().image_width) + "x" +
                                std::to_string(lut.grid().image_height) + " images, not " + std::to_string(image.cols) +
                                "x" + std::to_string(image.rows));
  }
  RestoredImage restored;
  restored.albedo = cv::Mat(image.size(), CV_32FC3, cv::Scalar::all(0));
  restored.confidence = cv::Mat(image.size(), CV_32FC3, cv::Scalar::all(0));
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      const float depth = maps.depth.at<float>(row, col);
      if (std::isnan(depth)) continue;
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      const Eigen::Vector3d point = (depth / direction.z()) * direction;
      const cv::Vec3f n = maps.normal.at<cv::Vec3f>(row, col);
      const double cos_theta = ShadingCosine(point, Eigen::Vector3d(n[0], n[1], n[2]), lut.grid().shading_light_in_cam);
      const double u = col + 0.5, v = row + 0.5;
      const LutNode node = lut.Lookup(u, v, depth);
      const cv::Vec3f observed = image.at<cv::Vec3f>(row, col);
      const Eigen::Vector3d intensity(observed[0], observed[1], observed[2]);
      const Eigen::Vector3d albedo = RestoreAlbedo(node.alpha, node.beta, cos_theta, intensity, options.model);
      const double grazing = GrazingConfidence(cos_theta, options.model);
      const Eigen::Vector3d covered = coverage ? coverage->Lookup(u, v, depth).alpha : Eigen::Vector3d::Ones();
      cv::Vec3f& out_albedo = restored.albedo.at<cv::Vec3f>(row, col);
      cv::Vec3f& out_confidence = restored.confidence.at<cv::Vec3f>(row, col);
      for (int c = 0; c < 3; ++c) {
        const double sigma = std::sqrt(options.shot_noise * options.shot_noise * std::max(intensity[c], 0.0) +
                                       options.read_noise * options.read_noise);
        const double signal = std::clamp((intensity[c] - node.beta[c]) / (options.signal_to_noise * sigma + 1e-12), 0.0, 1.0);
        const double unsaturated = intensity[c] >= options.saturation_level ? 0.0 : 1.0;
        const bool valid = std::isfinite(albedo[c]) && node.alpha[c] > 0.0;
        out_albedo[c] = valid ? static_cast<float>(albedo[c]) : 0.0f;
        out_confidence[c] = valid ? static_cast<float>(signal * unsaturated * grazing * std::clamp(covered[c], 0.0, 1.0)) : 0.0f;
      }
    }
  }
  return restored;
}

}  // namespace lutex
