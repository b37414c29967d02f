#include "lib/model/sensor.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace lutex {

void SensorOptions::Check() const {
  if (!(exposure > 0.0)) throw std::invalid_argument("sensor exposure must be positive");
  if (!(exposure_variation >= 0.0 && exposure_variation < 1.0)) {
    throw std::invalid_argument("sensor exposure_variation must be in [0, 1)");
  }
  if (blur_sigma_px < 0.0 || shot_noise < 0.0 || read_noise < 0.0) {
    throw std::invalid_argument("sensor blur and noise must not be negative");
  }
}

double ExposureFactor(const SensorOptions& options, std::uint64_t image_index) {
  if (options.exposure_variation == 0.0) return 1.0;
  // A generator of its own, so the noise of a scene without variation stays what it was.
  std::mt19937_64 random(options.seed * 0xD1B54A32D192ED03ull + image_index);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return 1.0 + options.exposure_variation * uniform(random);
}

cv::Mat ApplySensor(const cv::Mat& radiance, const SensorOptions& options, std::uint64_t image_index) {
  options.Check();
  cv::Mat value;
  radiance.convertTo(value, CV_32FC3, options.exposure * ExposureFactor(options, image_index));
  if (options.blur_sigma_px > 0.0) cv::GaussianBlur(value, value, cv::Size(0, 0), options.blur_sigma_px);
  if (options.shot_noise > 0.0 || options.read_noise > 0.0) {
    std::mt19937_64 random(options.seed * 0x9E3779B97F4A7C15ull + image_index);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int row = 0; row < value.rows; ++row) {
      auto* pixel = value.ptr<cv::Vec3f>(row);
      for (int col = 0; col < value.cols; ++col) {
        for (int c = 0; c < 3; ++c) {
          const double signal = std::max(0.0, static_cast<double>(pixel[col][c]));
          const double sigma = std::sqrt(options.shot_noise * options.shot_noise * signal +
                                         options.read_noise * options.read_noise);
          pixel[col][c] = static_cast<float>(signal + sigma * normal(random));
        }
      }
    }
  }
  return value;
}

}  // namespace lutex
