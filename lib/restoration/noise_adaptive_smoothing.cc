#include "lib/restoration/noise_adaptive_smoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace lutex {

namespace {

// sigma / E|n - median3x3(n)| for Gaussian noise n (measured over 250,000 samples: 0.723 sigma).
constexpr double kNoisePerMedianResidual = 1.383;
// The most a pixel's |rho - median3x3(rho)| counts in the noise estimate (full scale).
constexpr double kLargestResidual = 1.0;
// Restored values beyond +-this are averaged as +-this: with noise no smaller than kLeastNoise, squared
// colour distances then stay far below float's range.
constexpr float kLargestAlbedo = 1e6f;
// The noise of a region the estimate finds none in (flat and noise-free): below a 16-bit level.
constexpr float kLeastNoise = 1e-6f;

// Per channel, the median of the surface pixels in the 3 x 3 neighbourhood of (row, col) (itself included).
cv::Vec3f SurfaceMedian3x3(const cv::Mat& albedo, const cv::Mat& surface, int row, int col) {
  cv::Vec3f median;
  for (int c = 0; c < 3; ++c) {
    std::array<float, 9> values{};
    int count = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      const int y = row + dy;
      if (y < 0 || y >= albedo.rows) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = col + dx;
        if (x < 0 || x >= albedo.cols || !surface.at<std::uint8_t>(y, x)) continue;
        values[count++] = albedo.at<cv::Vec3f>(y, x)[c];
      }
    }
    std::nth_element(values.begin(), values.begin() + count / 2, values.begin() + count);
    median[c] = values[count / 2];
  }
  return median;
}

// The noise estimate of step 1 (header), CV_32FC3; undefined off the surface. The 3 x 3 median here is
// OpenCV's, which counts pixels off the surface as 0: the estimate rises a little along the surface's
// border, nowhere else.
// `on_surface`: CV_32F, 1 on the surface and 0 elsewhere.
cv::Mat NoiseOf(const cv::Mat& albedo, const cv::Mat& on_surface, int noise_radius) {
  cv::Mat median;
  cv::medianBlur(albedo, median, 3);
  cv::Mat residual = cv::abs(albedo - median);
  // A residual counts at most full scale: one absurd value (an alpha near 0) does not make its window noisy.
  cv::min(residual, cv::Scalar::all(kLargestResidual), residual);
  residual.setTo(cv::Scalar::all(0), on_surface == 0.0f);
  const cv::Size window(2 * noise_radius + 1, 2 * noise_radius + 1);
  cv::Mat residual_sum, count;
  cv::boxFilter(residual, residual_sum, CV_32F, window, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  cv::boxFilter(on_surface, count, CV_32F, window, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  cv::Mat noise(albedo.size(), CV_32FC3);
  for (int row = 0; row < albedo.rows; ++row) {
    const cv::Vec3f* sums = residual_sum.ptr<cv::Vec3f>(row);
    const float* counts = count.ptr<float>(row);
    cv::Vec3f* out = noise.ptr<cv::Vec3f>(row);
    for (int col = 0; col < albedo.cols; ++col) {
      const float scale = counts[col] > 0.5f ? static_cast<float>(kNoisePerMedianResidual) / counts[col] : 0.0f;
      out[col] = sums[col] * scale;
    }
  }
  return noise;
}

// Step 2 for `count` pixels of a row and their neighbours at one offset: c* the pixels' channels, s* their
// 1 / (cutoff x noise), n* the neighbours' channels, m 1 where a neighbour is on the surface; the weighted
// neighbours are added to sum* and their weights to weight_sum. Separate arrays, so that it vectorises.
void AccumulateNeighbours(int count, const float* __restrict c0, const float* __restrict c1,
                          const float* __restrict c2, const float* __restrict s0, const float* __restrict s1,
                          const float* __restrict s2, const float* __restrict n0, const float* __restrict n1,
                          const float* __restrict n2, const float* __restrict m, float* __restrict sum0,
                          float* __restrict sum1, float* __restrict sum2, float* __restrict weight_sum) {
  for (int i = 0; i < count; ++i) {
    const float d0 = (n0[i] - c0[i]) * s0[i], d1 = (n1[i] - c1[i]) * s1[i], d2 = (n2[i] - c2[i]) * s2[i];
    const float remaining = 1.0f - (d0 * d0 + d1 * d1 + d2 * d2);
    const float closeness = 0.5f * (remaining + std::fabs(remaining));  // max(remaining, 0) without a branch
    const float weight = closeness * closeness * m[i];
    sum0[i] += weight * n0[i];
    sum1[i] += weight * n1[i];
    sum2[i] += weight * n2[i];
    weight_sum[i] += weight;
  }
}

// One pass of steps 1-3 (header). `on_surface`: CV_32F, 1 on the surface and 0 elsewhere.
cv::Mat SmoothOnce(const cv::Mat& albedo, const cv::Mat& surface, const cv::Mat& on_surface,
                   const NoiseAdaptiveSmoothingOptions& options) {
  cv::Mat smoothed = albedo.clone();
  const cv::Mat noise = NoiseOf(albedo, on_surface, options.noise_radius);
  // Planes, so that the inner loop runs over contiguous floats of one row (and vectorises): the channels
  // and 1 / (cutoff x noise) per channel (and on_surface above).
  std::array<cv::Mat, 3> planes, scales;
  cv::split(albedo, planes.data());
  // Bounded, so that squared distances stay finite (a tiny alpha can restore to anything).
  for (cv::Mat& plane : planes) {
    cv::min(plane, kLargestAlbedo, plane);
    cv::max(plane, -kLargestAlbedo, plane);
  }
  cv::split(noise, scales.data());
  const float cutoff = static_cast<float>(options.cutoff);
  for (cv::Mat& scale : scales) {
    cv::max(scale, kLeastNoise, scale);
    cv::divide(1.0 / cutoff, scale, scale);
  }
  const int radius = options.radius, width = albedo.cols;
  std::vector<float> sum0(width), sum1(width), sum2(width), weight_sum(width);
  for (int row = 0; row < albedo.rows; ++row) {
    std::fill(sum0.begin(), sum0.end(), 0.0f);
    std::fill(sum1.begin(), sum1.end(), 0.0f);
    std::fill(sum2.begin(), sum2.end(), 0.0f);
    std::fill(weight_sum.begin(), weight_sum.end(), 0.0f);
    const float *c0 = planes[0].ptr<float>(row), *c1 = planes[1].ptr<float>(row), *c2 = planes[2].ptr<float>(row);
    const float *s0 = scales[0].ptr<float>(row), *s1 = scales[1].ptr<float>(row), *s2 = scales[2].ptr<float>(row);
    for (int y = std::max(0, row - radius); y <= std::min(albedo.rows - 1, row + radius); ++y) {
      const float *n0 = planes[0].ptr<float>(y), *n1 = planes[1].ptr<float>(y), *n2 = planes[2].ptr<float>(y);
      const float* m = on_surface.ptr<float>(y);
      for (int dx = -radius; dx <= radius; ++dx) {
        // Columns whose neighbour col + dx is inside the image.
        const int first = std::max(0, -dx), last = std::min(width, width - dx);
        AccumulateNeighbours(last - first, c0 + first, c1 + first, c2 + first, s0 + first, s1 + first, s2 + first,
                             n0 + first + dx, n1 + first + dx, n2 + first + dx, m + first + dx, sum0.data() + first,
                             sum1.data() + first, sum2.data() + first, weight_sum.data() + first);
      }
    }
    const std::uint8_t* centre_on_surface = surface.ptr<std::uint8_t>(row);
    cv::Vec3f* out = smoothed.ptr<cv::Vec3f>(row);
    for (int col = 0; col < width; ++col) {
      if (!centre_on_surface[col]) continue;
      // The centre itself weighs 1: a pixel whose neighbours weigh less than 1 together is unlike them all.
      if (!(weight_sum[col] >= 2.0f)) {
        out[col] = SurfaceMedian3x3(albedo, surface, row, col);
      } else {
        const float inverse = 1.0f / weight_sum[col];
        out[col] = cv::Vec3f(sum0[col] * inverse, sum1[col] * inverse, sum2[col] * inverse);
      }
    }
  }
  return smoothed;
}

}  // namespace

void NoiseAdaptiveSmoothingOptions::Check() const {
  if (radius < 1 || radius > 16) throw std::invalid_argument("noise-adaptive smoothing: radius must be 1 to 16 pixels");
  if (noise_radius < 1 || noise_radius > 64) {
    throw std::invalid_argument("noise-adaptive smoothing: the noise window's radius must be 1 to 64 pixels");
  }
  if (!(cutoff > 0.0 && std::isfinite(cutoff))) throw std::invalid_argument("noise-adaptive smoothing: cutoff must be positive");
  if (passes < 1 || passes > 16) throw std::invalid_argument("noise-adaptive smoothing: passes must be 1 to 16");
}

cv::Mat SmoothNoiseAdaptively(const cv::Mat& albedo, const cv::Mat& surface,
                              const NoiseAdaptiveSmoothingOptions& options) {
  options.Check();
  if (albedo.type() != CV_32FC3 || surface.type() != CV_8U || surface.size() != albedo.size()) {
    throw std::invalid_argument("noise-adaptive smoothing: a CV_32FC3 image and a CV_8U surface mask of its size");
  }
  if (!options.enabled || albedo.empty()) return albedo.clone();
  cv::Mat on_surface;
  cv::threshold(surface, on_surface, 0, 1, cv::THRESH_BINARY);
  on_surface.convertTo(on_surface, CV_32F);
  cv::Mat smoothed = albedo;  // each pass writes a new image: the input is never changed
  for (int pass = 0; pass < options.passes; ++pass) smoothed = SmoothOnce(smoothed, surface, on_surface, options);
  return smoothed;
}

}  // namespace lutex
