#include "lib/calibration/pure_water_sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "lib/util/median.h"

namespace lutex {

namespace {

constexpr int kThumbnailWidth = 160;

// The centre weights of a least-squares quadratic over 2 half + 1 samples (Savitzky-Golay smoothing):
// (3 (3 h^2 + 3 h - 1) - 15 i^2) / ((2 h + 1)(4 h^2 + 4 h - 3)) for i = -h .. h. They reproduce any
// quadratic exactly.
cv::Mat LocalQuadraticKernel(int half) {
  cv::Mat kernel(2 * half + 1, 1, CV_32F);
  const double h = half, denominator = (2 * h + 1) * (4 * h * h + 4 * h - 3);
  for (int i = -half; i <= half; ++i) {
    kernel.at<float>(i + half) = static_cast<float>((3 * (3 * h * h + 3 * h - 1) - 15.0 * i * i) / denominator);
  }
  return kernel;
}

// The image's smooth part: a local quadratic fit over (2 half + 1)^2 pixels, each axis in turn, with the
// image continued past its edges by point reflection through the edge pixel (2 I(edge) - I(mirror)), so that
// a gradient running into the border stays a gradient. Backscatter is smooth but curved and steepest at
// the image's edges, where a beam enters: a Gaussian-smoothed copy, with the image mirrored at its edges,
// flattened both, and a well-exposed turbid pure-water frame (harbour water, its brightest channel at 0.35
// of full scale at the 99th percentile) showed 5-6 % "structure" and was rejected.
cv::Mat SmoothFit(const cv::Mat& image, int half) {
  cv::Mat mirrored, replicated;
  cv::copyMakeBorder(image, mirrored, half, half, half, half, cv::BORDER_REFLECT_101);
  cv::copyMakeBorder(image, replicated, half, half, half, half, cv::BORDER_REPLICATE);
  const cv::Mat continued = 2.0 * replicated - mirrored;
  const cv::Mat kernel = LocalQuadraticKernel(half);
  cv::Mat fitted;
  cv::sepFilter2D(continued, fitted, CV_32F, kernel, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
  return fitted(cv::Rect(half, half, image.cols, image.rows)).clone();
}

// The noise of each channel, robustly from second differences along rows, 1.4826 median |I(x - 1) - 2 I(x)
// + I(x + 1)| / sqrt(6): they cancel a smooth gradient, and a surface's edges touch few of them however much
// of the image the surface fills. (It was the median departure from the smooth fit, which a surface that
// fills the frame makes as large as its own contrast: a seafloor of 25 cm cells filling the view was no
// structure at all.) Measured before the median filter, so it is at least the noise left after it.
std::array<double, 3> NoiseLevel(const cv::Mat& image) {
  std::array<double, 3> noise{};
  if (image.cols < 3) return noise;
  std::array<std::vector<double>, 3> values;
  for (int row = 0; row < image.rows; ++row) {
    const auto* pixels = image.ptr<cv::Vec3f>(row);
    for (int col = 1; col + 1 < image.cols; ++col) {
      for (int c = 0; c < 3; ++c) values[c].push_back(std::abs(pixels[col - 1][c] - 2.0 * pixels[col][c] + pixels[col + 1][c]));
    }
  }
  for (int c = 0; c < 3; ++c) noise[c] = 1.4826 * MedianInPlace(values[c]) / std::sqrt(6.0);
  return noise;
}

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
  cv::Mat thumbnail;
  cv::resize(linear, thumbnail, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  const std::array<double, 3> noise = NoiseLevel(thumbnail);
  // Isolated outliers (fireflies, hot pixels, a particle) are not a surface: a 3 x 3 median removes them
  // and keeps edges and lines two pixels wide.
  cv::medianBlur(cv::Mat(thumbnail), thumbnail, 3);
  // Over 39 pixels of the 160-pixel thumbnail: wide enough that a surface's edge stands out of it.
  const int half = std::max(1, std::min({static_cast<int>(std::lround(width * 3.0 / 25.0)), (width - 1) / 2,
                                         (height - 1) / 2}));
  const cv::Mat smooth = SmoothFit(thumbnail, half);
  const cv::Mat deviation = cv::abs(thumbnail - smooth);
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
