#include "lib/restoration/restorer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lib/lut/lut_image_sampler.h"

namespace lutex {
namespace {

// clamp(signal / (k sigma), 0, 1) from (k sigma)^2; the square root only where the signal is within k sigma
// (few pixels: this runs for every pixel and channel of every image).
float SignalConfidence(float signal, float squared_k_sigma) {
  if (!(signal > 0.0f)) return 0.0f;
  const float squared_signal = signal * signal;
  return squared_signal >= squared_k_sigma ? 1.0f : std::sqrt(squared_signal / squared_k_sigma);
}

}  // namespace

void RestorationOptions::Check() const {
  if (!(model.min_cos_theta > 0.0 && model.min_cos_theta < 1.0)) throw std::invalid_argument("min_cos_theta must be in (0, 1)");
  if (!(saturation_level > 0.0)) throw std::invalid_argument("saturation_level must be positive");
  if (shot_noise < 0.0 || read_noise < 0.0 || !(signal_to_noise > 0.0)) {
    throw std::invalid_argument("noise model needs shot_noise, read_noise >= 0 and signal_to_noise > 0");
  }
}

RestoredImage RestoreImage(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays, const FrustumLut& lut,
                           const RestorationOptions& options, const FrustumLut* coverage) {
  RestoredImage restored;
  RestoreImage(image, maps, rays, lut, options, coverage, &restored);
  return restored;
}

void RestoreImage(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays, const FrustumLut& lut,
                  const RestorationOptions& options, const FrustumLut* coverage, RestoredImage* output) {
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
  const LutImageSampler sampler(lut, coverage);
  const Shading& shading = lut.grid().shading;
  const float shot_variance = static_cast<float>(options.shot_noise * options.shot_noise);
  const float read_variance = static_cast<float>(options.read_noise * options.read_noise);
  const float squared_snr = static_cast<float>(options.signal_to_noise * options.signal_to_noise);
  const float saturation_level = static_cast<float>(options.saturation_level);
  RestoredImage& restored = *output;
  restored.albedo.create(image.size(), CV_32FC3);
  restored.confidence.create(image.size(), CV_32FC3);
  LutImageSampler::RowSampler row_sampler;
  for (int row = 0; row < image.rows; ++row) {
    sampler.PrepareRow(row, &row_sampler);
    const float* depth_row = maps.depth.ptr<float>(row);
    const cv::Vec3f* normal_row = maps.normal.ptr<cv::Vec3f>(row);
    const cv::Vec3f* observed_row = image.ptr<cv::Vec3f>(row);
    cv::Vec3f* albedo_row = restored.albedo.ptr<cv::Vec3f>(row);
    cv::Vec3f* confidence_row = restored.confidence.ptr<cv::Vec3f>(row);
    for (int col = 0; col < image.cols; ++col) {
      albedo_row[col] = confidence_row[col] = cv::Vec3f(0.0f, 0.0f, 0.0f);
      const float depth = depth_row[col];
      if (std::isnan(depth)) continue;
      const Eigen::Vector3f& direction = rays.Direction(col, row);
      const Eigen::Vector3f point = (depth / direction.z()) * direction;
      const float cos_theta = shading.Cosine(point, Eigen::Vector3f(normal_row[col][0], normal_row[col][1], normal_row[col][2]));
      const float grazing = GrazingConfidence(cos_theta, options.model);
      const LutPixelSample lut_here = row_sampler.At(col, depth);
      for (int c = 0; c < 3; ++c) {
        const float intensity = observed_row[col][c];
        const float albedo = RestoreChannel(lut_here.alpha[c], lut_here.beta[c], cos_theta, intensity, options.model);
        if (!(lut_here.alpha[c] > 0.0f) || !std::isfinite(albedo)) continue;
        const float signal = SignalConfidence(intensity - lut_here.beta[c],
                                              squared_snr * (shot_variance * std::max(intensity, 0.0f) + read_variance));
        const float unsaturated = intensity >= saturation_level ? 0.0f : 1.0f;
        albedo_row[col][c] = albedo;
        confidence_row[col][c] = signal * unsaturated * grazing * std::clamp(lut_here.coverage[c], 0.0f, 1.0f);
      }
    }
  }
}

}  // namespace lutex
