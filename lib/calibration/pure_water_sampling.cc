#include "lib/calibration/pure_water_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "lib/util/median.h"

namespace lutex {

namespace {

constexpr int kThumbnailWidth = 160;

}  // namespace

void PureWaterScreeningOptions::Check() const {
  if (!(max_structure > 0.0) || !(max_brightness_ratio > 1.0)) {
    throw std::invalid_argument("pure-water screening needs max_structure > 0 and max_brightness_ratio > 1");
  }
}

PureWaterImageStats MeasurePureWaterImage(const cv::Mat& linear) {
  CV_Assert(linear.type() == CV_32FC3 && !linear.empty());
  PureWaterImageStats stats;
  const cv::Scalar mean = cv::mean(linear);
  stats.mean = Eigen::Vector3d(mean[0], mean[1], mean[2]);
  const int width = std::min(kThumbnailWidth, linear.cols);
  const int height = std::max(1, static_cast<int>(std::lround(static_cast<double>(linear.rows) * width / linear.cols)));
  cv::Mat thumbnail, smooth;
  cv::resize(linear, thumbnail, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  // Isolated outliers (fireflies, hot pixels, a particle) are not a surface: a 3 x 3 median removes them
  // and keeps edges and lines two pixels wide.
  cv::medianBlur(cv::Mat(thumbnail), thumbnail, 3);
  cv::GaussianBlur(thumbnail, smooth, cv::Size(), width / 25.0);
  cv::Mat deviation = cv::abs(thumbnail - smooth);
  // The image's own noise level (robust: surface edges touch few pixels), per channel.
  std::vector<cv::Mat> channels;
  cv::split(deviation, channels);
  double noise[3];
  for (int c = 0; c < 3; ++c) {
    std::vector<double> values(channels[c].begin<float>(), channels[c].end<float>());
    noise[c] = 1.4826 * MedianInPlace(values);
  }
  int structured = 0;
  for (int row = 0; row < thumbnail.rows; ++row) {
    for (int col = 0; col < thumbnail.cols; ++col) {
      const cv::Vec3f off = deviation.at<cv::Vec3f>(row, col);
      const cv::Vec3f expected = smooth.at<cv::Vec3f>(row, col);
      for (int c = 0; c < 3; ++c) {
        if (off[c] > std::max(0.003 + 0.05 * expected[c], 5.0 * noise[c])) {
          ++structured;
          break;
        }
      }
    }
  }
  stats.structure = static_cast<double>(structured) / static_cast<double>(thumbnail.total());
  return stats;
}

std::vector<std::string> ScreenPureWaterImages(const std::vector<PureWaterImageStats>& images,
                                               const PureWaterScreeningOptions& options) {
  options.Check();
  std::vector<std::string> reasons(images.size());
  if (images.empty()) return reasons;
  // Open water is the darkest thing the rig can look at (a lit surface only adds light), so the
  // brightness is judged against the darker images of the set: its lower quartile, which stays open
  // water while up to three in four images show a surface.
  Eigen::Vector3d reference_mean;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> means;
    for (const PureWaterImageStats& image : images) means.push_back(image.mean[c]);
    const auto quartile = means.begin() + static_cast<long>(means.size() / 4);
    std::nth_element(means.begin(), quartile, means.end());
    reference_mean[c] = *quartile;
  }
  char text[160];
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (images[i].structure > options.max_structure) {
      std::snprintf(text, sizeof(text), "%.1f %% of the image has structure (edges), more than backscatter has",
                    100.0 * images[i].structure);
      reasons[i] = text;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const double limit = options.max_brightness_ratio * reference_mean[c] + 0.002;
      if (images[i].mean[c] > limit) {
        std::snprintf(text, sizeof(text), "%.0f times brighter than the darker pure-water images",
                      images[i].mean[c] / std::max(reference_mean[c], 1e-6));
        reasons[i] = text;
        break;
      }
    }
  }
  return reasons;
}

std::vector<PureWaterObservation> SamplePureWater(const cv::Mat& linear, int stride) {
  CV_Assert(linear.type() == CV_32FC3 && stride >= 1);
  std::vector<PureWaterObservation> observations;
  for (int row = stride / 2; row < linear.rows; row += stride) {
    for (int col = stride / 2; col < linear.cols; col += stride) {
      const cv::Vec3f value = linear.at<cv::Vec3f>(row, col);
      PureWaterObservation observation;
      observation.pixel = Eigen::Vector2d(col + 0.5, row + 0.5);
      observation.intensity = Eigen::Vector3d(value[0], value[1], value[2]);
      observations.push_back(observation);
    }
  }
  return observations;
}

}  // namespace lutex
