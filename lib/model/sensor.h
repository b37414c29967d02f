#pragma once

// What a camera adds to the radiance reaching it, for simulated images: exposure (radiance to [0, 1],
// optionally varying from frame to frame),
// an optional forward-scatter blur, shot noise (Gaussian with variance proportional to the signal) and
// read noise, from a seeded generator so every image is reproducible. Quantisation happens when the image
// is encoded (image_io.h: 8-bit sRGB or 16-bit linear).

#include <cstdint>

#include <opencv2/core.hpp>

namespace lutex {

struct SensorOptions {
  // Multiplies radiance into the [0, 1] pixel range.
  double exposure = 1.0;
  // Frame-to-frame variation (a strobe's power, an auto exposure): each image's exposure is multiplied by
  // ExposureFactor, drawn uniformly from [1 - v, 1 + v] for the image; 0 = every image alike.
  double exposure_variation = 0.0;
  // Standard deviation of a Gaussian blur in pixels (forward scattering); 0 = none.
  double blur_sigma_px = 0.0;
  // Shot noise: sigma = shot_noise * sqrt(value), value in [0, 1] after exposure.
  double shot_noise = 0.0;
  // Read noise: additive sigma, in [0, 1] units.
  double read_noise = 0.0;
  std::uint64_t seed = 1;

  // Throws std::invalid_argument on nonsense.
  void Check() const;
};

// The factor image `image_index`'s exposure is multiplied by (1 without variation); reproducible from
// the seed.
double ExposureFactor(const SensorOptions& options, std::uint64_t image_index);

// Linear RGB CV_32FC3 in, linear RGB CV_32FC3 out (not clamped). `image_index` varies the noise and the
// exposure factor per image.
cv::Mat ApplySensor(const cv::Mat& radiance, const SensorOptions& options, std::uint64_t image_index);

}  // namespace lutex
