#include "lib/model/forward_scatter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace lutex {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Samples of the angle over [0, pi] for the kernel's integrals: 0.02 degrees apart, fine against the
// phase function's peak (about (1 - g) radians wide, 0.1 for g = 0.9; 0.01 for g = 0.99).
constexpr int kAngleSamples = 8192;
// The finest blur taken out, in pixels. Undoing finer blur mostly amplifies the pixels' own noise: on the
// Blender turbid sets (README, 'Forward scattering') a finest sigma of 1, 2, 4 and 8 px gave a seafloor
// error of 11.6, 11.3, 10.8 and 10.3 pp and a worst ColorChecker patch of 12.9, 12.9, 13.6 and 16.4 pp.
constexpr double kFinestSigmaPx = 4.0;

// E(phi) on the samples phi_i = i * pi / kAngleSamples, i <= kAngleSamples / 2 (phi up to pi / 2).
std::vector<double> EnergyTable(double g) {
  const double step = kPi / kAngleSamples;
  std::vector<double> phase(kAngleSamples + 1);
  for (int i = 0; i <= kAngleSamples; ++i) phase[i] = HenyeyGreenstein(std::cos(i * step), g);
  // tail[i] = integral from phi_i to pi of p(theta) dtheta (trapezoids).
  std::vector<double> tail(kAngleSamples + 1, 0.0);
  for (int i = kAngleSamples - 1; i >= 0; --i) tail[i] = tail[i + 1] + 0.5 * (phase[i] + phase[i + 1]) * step;
  // The radial density 2 pi sin(phi) k(phi) = 2 pi sin(phi) tail(phi) / phi, which tends to 2 pi tail(0).
  const int half = kAngleSamples / 2;
  const auto density = [&](int i) { return i == 0 ? 2.0 * kPi * tail[0] : 2.0 * kPi * std::sin(i * step) * tail[i] / (i * step); };
  std::vector<double> energy(half + 1, 0.0);
  for (int i = 1; i <= half; ++i) energy[i] = energy[i - 1] + 0.5 * (density(i - 1) + density(i)) * step;
  for (double& e : energy) e /= energy[half];
  return energy;
}

double Interpolate(const std::vector<double>& energy, double phi) {
  const double position = std::clamp(phi, 0.0, kPi / 2) / (kPi / kAngleSamples);
  const int i = std::min(static_cast<int>(position), static_cast<int>(energy.size()) - 2);
  const double f = position - i;
  return energy[i] * (1.0 - f) + energy[i + 1] * f;
}

// The pyramid level a Gaussian of sigma pixels runs on: the image halved `level` times, where its sigma is
// 2 to 4 pixels (level 0 for sigma below 4).
int LevelOf(double sigma) { return sigma < 4.0 ? 0 : static_cast<int>(std::floor(std::log2(sigma / 2.0))); }

// The sigma to blur with on `level` so that, with the variance the way down adds (2 x 2 area averages:
// (4^L - 1) / 12 px^2 over all levels) and the way up (bilinear doubling, 3/16 of the squared spacing per
// step: (4^L - 1) / 4), a point is spread by sigma in the image's pixels.
double SigmaOnLevel(double sigma, int level) {
  const double factor = std::ldexp(1.0, level);
  const double added = (factor * factor - 1.0) / 3.0;
  return std::sqrt(std::max(sigma * sigma - added, 0.25 * factor * factor)) / factor;
}

cv::Size Halved(const cv::Size& size) { return {(size.width + 1) / 2, (size.height + 1) / 2}; }

// 1 - t = 1 - exp(-b d) per pixel and channel, 0 where there is no surface.
cv::Mat ScatteredFraction(const cv::Mat& range, const Eigen::Vector3d& scattering_per_m) {
  cv::Mat fraction(range.size(), CV_32FC3);
  for (int row = 0; row < range.rows; ++row) {
    const float* d = range.ptr<float>(row);
    cv::Vec3f* out = fraction.ptr<cv::Vec3f>(row);
    for (int col = 0; col < range.cols; ++col) {
      for (int c = 0; c < 3; ++c) {
        out[col][c] = std::isfinite(d[col]) ? static_cast<float>(1.0 - std::exp(-scattering_per_m[c] * d[col])) : 0.0f;
      }
    }
  }
  return fraction;
}

void ExpectImageAndRange(const cv::Mat& image, const cv::Mat& range) {
  if (image.type() != CV_32FC3 || range.type() != CV_32F || image.size() != range.size()) {
    throw std::invalid_argument("forward scattering needs a CV_32FC3 image and a CV_32F range map of its size");
  }
}

}  // namespace

std::string DescribeForwardScatter(const ForwardScatter& scatter) {
  char text[120];
  std::snprintf(text, sizeof(text), "b %.3f %.3f %.3f per m (r g b), g %.2f", scatter.scattering.x(),
                scatter.scattering.y(), scatter.scattering.z(), scatter.anisotropy_g);
  return text;
}

ForwardScatter ForwardScatter::Of(const Water& water) {
  ForwardScatter scatter;
  scatter.scattering = water.scattering;
  scatter.anisotropy_g = water.anisotropy_g;
  return scatter;
}

void ForwardScatter::Check() const {
  if (!scattering.allFinite() || (scattering.array() < 0.0).any()) {
    throw std::invalid_argument("forward scattering: the scattering coefficients must be finite and >= 0");
  }
  if (!std::isfinite(anisotropy_g) || anisotropy_g < 0.0 || anisotropy_g >= 1.0) {
    throw std::invalid_argument("forward scattering: the anisotropy g must lie in [0, 1)");
  }
}

double ForwardScatterEnergyWithin(double phi_rad, double anisotropy_g) {
  return Interpolate(EnergyTable(anisotropy_g), phi_rad);
}

ForwardScatterKernel MakeForwardScatterKernel(double anisotropy_g, double focal_px) {
  if (!(focal_px > 0.0) || !std::isfinite(focal_px)) throw std::invalid_argument("forward scattering: focal length must be > 0");
  const std::vector<double> energy = EnergyTable(anisotropy_g);
  const auto within_px = [&](double radius_px) { return Interpolate(energy, std::atan(radius_px / focal_px)); };
  // Gaussian i has sigma 2^i kFinestSigmaPx pixels; its median radius is sigma sqrt(2 ln 2). It takes the
  // kernel's energy between the geometric means of its median radius and its neighbours'. Within the first
  // bound (3.3 px) the kernel stays on the pixel.
  const double median_per_sigma = std::sqrt(2.0 * std::log(2.0));
  ForwardScatterKernel kernel;
  double inner = kFinestSigmaPx * median_per_sigma / std::sqrt(2.0);
  kernel.identity_weight = within_px(inner);
  double placed = kernel.identity_weight;
  for (double sigma = kFinestSigmaPx; placed < 1.0; sigma *= 2.0) {
    const double outer = sigma * median_per_sigma * std::sqrt(2.0);
    // The last Gaussian takes everything up to pi / 2 (beyond which the scattered light comes from
    // behind the camera's image plane and is negligible for forward-peaked water).
    const bool last = std::atan(outer / focal_px) >= 89.0 * kPi / 180.0;
    const double upto = last ? 1.0 : within_px(outer);
    kernel.sigma_px.push_back(sigma);
    kernel.weight.push_back(upto - placed);
    placed = upto;
    inner = outer;
  }
  return kernel;
}

namespace {

// The Gaussians of `kernel` applied to `image` and summed, without the part that stays on the pixel.
cv::Mat SpreadPart(const cv::Mat& image, const ForwardScatterKernel& kernel) {
  // One pyramid for all Gaussians: down by area averages, each Gaussian blurred on its level and added to
  // the sum there, the sum carried up level by level. The full-size image is read and written about twice
  // per convolution, whatever the number of Gaussians.
  int top = 0;
  for (const double sigma : kernel.sigma_px) top = std::max(top, LevelOf(sigma));
  std::vector<cv::Mat> pyramid{image};
  for (int level = 1; level <= top; ++level) {
    cv::Mat smaller;
    cv::resize(pyramid.back(), smaller, Halved(pyramid.back().size()), 0, 0, cv::INTER_AREA);
    pyramid.push_back(smaller);
  }
  cv::Mat sum;
  for (int level = top; level >= 0; --level) {
    if (!sum.empty()) {
      cv::Mat larger;
      cv::resize(sum, larger, pyramid[level].size(), 0, 0, cv::INTER_LINEAR);
      sum = larger;
    } else {
      sum = cv::Mat::zeros(pyramid[level].size(), image.type());
    }
    for (std::size_t i = 0; i < kernel.sigma_px.size(); ++i) {
      if (kernel.weight[i] <= 0.0 || LevelOf(kernel.sigma_px[i]) != level) continue;
      const double sigma = SigmaOnLevel(kernel.sigma_px[i], level);
      cv::Mat blurred;
      cv::GaussianBlur(pyramid[level], blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT);
      cv::scaleAdd(blurred, kernel.weight[i], sum, sum);
    }
  }
  return sum;
}

}  // namespace

cv::Mat ConvolveForwardScatterKernel(const cv::Mat& image, const ForwardScatterKernel& kernel) {
  cv::Mat sum = SpreadPart(image, kernel);
  cv::scaleAdd(image, kernel.identity_weight, sum, sum);
  return sum;
}

cv::Mat AddForwardScatter(const cv::Mat& radiance, const cv::Mat& range, const ForwardScatterKernel& kernel,
                          const Eigen::Vector3d& scattering_per_m) {
  ExpectImageAndRange(radiance, range);
  const cv::Mat fraction = ScatteredFraction(range, scattering_per_m);
  const cv::Mat spread = ConvolveForwardScatterKernel(radiance, kernel);
  // t R + (1 - t) (k * R) = R + (1 - t) (k * R - R)
  return radiance + fraction.mul(spread - radiance);
}

cv::Mat RemoveForwardScatter(const cv::Mat& image, const cv::Mat& range, const ForwardScatterKernel& kernel,
                             const Eigen::Vector3d& scattering_per_m, int iterations) {
  ExpectImageAndRange(image, range);
  const cv::Mat fraction = ScatteredFraction(range, scattering_per_m);
  // The model is A R = R + F (k * R - R) with F = 1 - t, and k * R - R = spread(R) - leaving R. The
  // eigenvalues of A lie in [1 - m, 1], m = max F * leaving (the Gaussians' spectra lie in (0, 1]), so
  // A R = S is solved by Chebyshev iteration over that interval, one convolution per step: its error
  // shrinks by (sqrt(kappa) - 1) / (sqrt(kappa) + 1) per step, kappa = 1 / (1 - m), where the plain series
  // R = S - F (k * R - R) shrinks by m (3 steps instead of 8 for a scattered fraction of 0.65).
  const double leaving = 1.0 - kernel.identity_weight;
  double largest_fraction = 0.0;
  cv::minMaxLoc(fraction.reshape(1), nullptr, &largest_fraction);
  const double m = std::min(largest_fraction * leaving, 0.999);
  const double centre = 1.0 - 0.5 * m, half_width = 0.5 * m;
  cv::Mat restored = image.clone();
  if (m <= 0.0) return restored;
  cv::Mat direction(image.size(), CV_32FC3, cv::Scalar::all(0.0));
  const float leaving_f = static_cast<float>(leaving);
  double step = 0.0;
  for (int i = 0; i < iterations; ++i) {
    double beta = 0.0;
    if (i == 0) {
      step = 1.0 / centre;
    } else {
      beta = i == 1 ? 0.5 * (half_width * step) * (half_width * step) : (0.5 * half_width * step) * (0.5 * half_width * step);
      step = 1.0 / (centre - beta / step);
    }
    // In one pass: the residual S - A R, the direction r + beta p, and R + step p.
    const cv::Mat spread = SpreadPart(restored, kernel);
    const auto beta_f = static_cast<float>(beta), step_f = static_cast<float>(step);
    for (int row = 0; row < image.rows; ++row) {
      const cv::Vec3f* observed = image.ptr<cv::Vec3f>(row);
      const cv::Vec3f* scattered = fraction.ptr<cv::Vec3f>(row);
      const cv::Vec3f* arrived = spread.ptr<cv::Vec3f>(row);
      cv::Vec3f* value = restored.ptr<cv::Vec3f>(row);
      cv::Vec3f* towards = direction.ptr<cv::Vec3f>(row);
      for (int col = 0; col < image.cols; ++col) {
        for (int c = 0; c < 3; ++c) {
          const float residual =
              observed[col][c] - value[col][c] - scattered[col][c] * (arrived[col][c] - leaving_f * value[col][c]);
          towards[col][c] = residual + beta_f * towards[col][c];
          value[col][c] += step_f * towards[col][c];
        }
      }
    }
  }
  return cv::max(restored, 0.0);
}

}  // namespace lutex
