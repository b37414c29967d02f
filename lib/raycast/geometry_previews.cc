#include "lib/raycast/geometry_previews.h"

#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace lutex {

cv::Mat DepthPreview(const cv::Mat& depth) {
  CV_Assert(depth.type() == CV_32F);
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (int row = 0; row < depth.rows; ++row) {
    for (int col = 0; col < depth.cols; ++col) {
      const float z = depth.at<float>(row, col);
      if (std::isfinite(z)) {
        lowest = std::min<double>(lowest, z);
        highest = std::max<double>(highest, z);
      }
    }
  }
  cv::Mat scaled(depth.size(), CV_8U, cv::Scalar(0));
  const cv::Mat valid = depth == depth;  // false for NaN
  if (highest > lowest) {
    depth.convertTo(scaled, CV_8U, 255.0 / (highest - lowest), -255.0 * lowest / (highest - lowest));
  }
  cv::Mat preview;
  cv::applyColorMap(scaled, preview, cv::COLORMAP_TURBO);
  preview.setTo(cv::Scalar::all(0), ~valid);
  return preview;
}

cv::Mat NormalPreview(const cv::Mat& normal) {
  CV_Assert(normal.type() == CV_32FC3);
  cv::Mat rgb;
  normal.convertTo(rgb, CV_8UC3, 127.5, 127.5);
  cv::Mat preview;
  cv::cvtColor(rgb, preview, cv::COLOR_RGB2BGR);
  std::vector<cv::Mat> channels;
  cv::split(normal, channels);
  preview.setTo(cv::Scalar::all(0), channels[0] != channels[0]);
  return preview;
}

}  // namespace lutex
