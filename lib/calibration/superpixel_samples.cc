#include "lib/calibration/superpixel_samples.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/slic.hpp>

#include "lib/image/image_io.h"
#include "lib/model/image_formation.h"
#include "lib/util/median.h"

namespace lutex {

namespace {

// 8-bit sRGB Lab of a linear image: SLIC's colour distance is meant for a perceptual space.
cv::Mat PerceptualLab(const cv::Mat& linear) {
  cv::Mat lab;
  cv::cvtColor(EncodeLinearImage(linear, ImageEncoding::kSrgb8), lab, cv::COLOR_BGR2Lab);
  return lab;
}

// Distance (pixels) of every pixel to the nearest pixel of another superpixel or the image border.
cv::Mat DistanceInsideSuperpixel(const cv::Mat& labels) {
  cv::Mat interior(labels.size(), CV_8U, cv::Scalar(0));
  for (int row = 1; row + 1 < labels.rows; ++row) {
    for (int col = 1; col + 1 < labels.cols; ++col) {
      const int label = labels.at<int>(row, col);
      interior.at<uchar>(row, col) = labels.at<int>(row - 1, col) == label && labels.at<int>(row + 1, col) == label &&
                                     labels.at<int>(row, col - 1) == label && labels.at<int>(row, col + 1) == label;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(interior, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance;
}

}  // namespace

void SuperpixelOptions::Check() const {
  if (count < 1 || working_width < 16) throw std::invalid_argument("superpixels need count >= 1 and working_width >= 16");
  if (!(min_cos_theta > 0.0 && min_cos_theta < 1.0)) throw std::invalid_argument("min_cos_theta must be in (0, 1)");
  if (!(max_relative_depth_range > 0.0) || !(max_relative_color_spread > 0.0)) {
    throw std::invalid_argument("superpixel depth and colour tolerances must be positive");
  }
}

std::vector<SurfaceSample> SampleSuperpixels(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                                             const SuperpixelOptions& options) {
  options.Check();
  CV_Assert(image.type() == CV_32FC3 && image.cols == rays.width() && image.rows == rays.height());
  CV_Assert(maps.depth.size() == image.size() && maps.normal.size() == image.size());
  const double scale = image.cols > options.working_width ? static_cast<double>(options.working_width) / image.cols : 1.0;
  cv::Mat working = image;
  if (scale < 1.0) {
    cv::resize(image, working, cv::Size(), scale, scale, cv::INTER_AREA);
  }
  const int region_size =
      std::max(4, static_cast<int>(std::lround(std::sqrt(static_cast<double>(working.total()) / options.count))));
  const cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic =
      cv::ximgproc::createSuperpixelSLIC(PerceptualLab(working), cv::ximgproc::SLICO, region_size);
  slic->iterate(10);
  slic->enforceLabelConnectivity(25);
  cv::Mat labels;
  slic->getLabels(labels);
  const int num_labels = slic->getNumberOfSuperpixels();
  const cv::Mat distance = DistanceInsideSuperpixel(labels);

  // The most interior pixel of every superpixel.
  std::vector<cv::Point> centre(static_cast<std::size_t>(num_labels), cv::Point(-1, -1));
  std::vector<float> depth_inside(static_cast<std::size_t>(num_labels), 0.0f);
  for (int row = 0; row < labels.rows; ++row) {
    for (int col = 0; col < labels.cols; ++col) {
      const auto label = static_cast<std::size_t>(labels.at<int>(row, col));
      if (distance.at<float>(row, col) > depth_inside[label]) {
        depth_inside[label] = distance.at<float>(row, col);
        centre[label] = cv::Point(col, row);
      }
    }
  }
  // Inner pixels: at least a third of the superpixel's inscribed radius inside.
  const auto full_pixel = [&](int col, int row) {
    return cv::Point(std::min(image.cols - 1, static_cast<int>((col + 0.5) / scale)),
                     std::min(image.rows - 1, static_cast<int>((row + 0.5) / scale)));
  };
  std::vector<std::vector<float>> red(static_cast<std::size_t>(num_labels)), green(red.size()), blue(red.size()),
      depths(red.size());
  std::vector<bool> rejected(red.size(), false);
  for (int row = 0; row < labels.rows; ++row) {
    for (int col = 0; col < labels.cols; ++col) {
      const auto label = static_cast<std::size_t>(labels.at<int>(row, col));
      if (rejected[label] || distance.at<float>(row, col) < std::max(1.0f, depth_inside[label] / 3.0f)) continue;
      const cv::Vec3f value = working.at<cv::Vec3f>(row, col);
      const float depth = maps.depth.at<float>(full_pixel(col, row));
      if (std::isnan(depth) || std::max({value[0], value[1], value[2]}) >= options.saturation_level) {
        rejected[label] = true;
        continue;
      }
      red[label].push_back(value[0]);
      green[label].push_back(value[1]);
      blue[label].push_back(value[2]);
      depths[label].push_back(depth);
    }
  }

  std::vector<SurfaceSample> samples;
  for (std::size_t label = 0; label < red.size(); ++label) {
    if (rejected[label] || depth_inside[label] < 2.0f || green[label].size() < 5) continue;
    const auto [lowest, highest] = std::minmax_element(depths[label].begin(), depths[label].end());
    const double median_depth = MedianInPlace(depths[label]);
    if (*highest - *lowest > options.max_relative_depth_range * median_depth) continue;
    const Eigen::Vector3d color(MedianInPlace(red[label]), MedianInPlace(green[label]), MedianInPlace(blue[label]));
    if (!(color.y() > 0.0) ||
        MedianAbsoluteDeviation(green[label], color.y()) > options.max_relative_color_spread * color.y()) {
      continue;
    }
    const cv::Point pixel = full_pixel(centre[label].x, centre[label].y);
    const float depth = maps.depth.at<float>(pixel);
    const cv::Vec3f normal = maps.normal.at<cv::Vec3f>(pixel);
    if (std::isnan(depth)) continue;
    SurfaceSample sample;
    const Eigen::Vector3d direction = rays.Direction(pixel.x, pixel.y).cast<double>();
    sample.view.pixel = Eigen::Vector2d(pixel.x + 0.5, pixel.y + 0.5);
    sample.view.point_in_cam = (depth / direction.z()) * direction;
    sample.view.normal_in_cam = Eigen::Vector3d(normal[0], normal[1], normal[2]);
    sample.view.cos_theta = options.shading.Cosine(sample.view.point_in_cam, sample.view.normal_in_cam);
    if (sample.view.cos_theta < options.min_cos_theta) continue;
    sample.view.intensity = color;
    sample.footprint_radius = std::max(1.0, 0.5 * depth_inside[label] / scale);
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace lutex
