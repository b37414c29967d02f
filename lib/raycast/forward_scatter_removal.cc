#include "lib/raycast/forward_scatter_removal.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "lib/lut/lut_image_sampler.h"

namespace lutex {

cv::Mat RangeAlongRays(const GeometryMaps& maps, const CameraRays& rays) {
  if (maps.origin != cv::Point(0, 0) || maps.depth.cols != rays.width() || maps.depth.rows != rays.height()) {
    throw std::invalid_argument("RangeAlongRays needs the maps of the whole image");
  }
  cv::Mat range(maps.depth.size(), CV_32F);
  for (int row = 0; row < range.rows; ++row) {
    const float* depth = maps.depth.ptr<float>(row);
    float* out = range.ptr<float>(row);
    for (int col = 0; col < range.cols; ++col) {
      const float z_of_ray = rays.Direction(col, row).z();
      out[col] = std::isfinite(depth[col]) && z_of_ray > 0.0f ? depth[col] / z_of_ray
                                                              : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return range;
}

cv::Mat BackscatterAtSurfaces(const FrustumLut& lut, const GeometryMaps& maps, double gain) {
  const FrustumLutGrid& grid = lut.grid();
  if (maps.origin != cv::Point(0, 0) || maps.depth.cols != grid.image_width || maps.depth.rows != grid.image_height) {
    throw std::invalid_argument("BackscatterAtSurfaces needs the maps of the LUT's whole image");
  }
  const LutImageSampler sampler(lut);
  LutImageSampler::RowSampler row_sampler;
  cv::Mat backscatter(maps.depth.size(), CV_32FC3, cv::Scalar::all(0));
  const auto scale = static_cast<float>(gain);
  for (int row = 0; row < backscatter.rows; ++row) {
    sampler.PrepareRow(row, &row_sampler);
    const float* depth = maps.depth.ptr<float>(row);
    cv::Vec3f* out = backscatter.ptr<cv::Vec3f>(row);
    for (int col = 0; col < backscatter.cols; ++col) {
      if (!std::isfinite(depth[col])) continue;
      const LutPixelSample sample = row_sampler.At(col, depth[col]);
      out[col] = cv::Vec3f(scale * sample.beta[0], scale * sample.beta[1], scale * sample.beta[2]);
    }
  }
  return backscatter;
}

cv::Mat WithoutForwardScatter(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                              const ForwardScatter& scatter, double saturation_level, const cv::Mat& backscatter) {
  if (scatter.IsNone()) return image;
  if (!backscatter.empty() && (backscatter.size() != image.size() || backscatter.type() != CV_32FC3)) {
    throw std::invalid_argument("WithoutForwardScatter: the backscatter must be CV_32FC3 of the image's size");
  }
  const Camera& camera = rays.camera();
  const double focal_px = 0.5 * (camera.FocalLengthX() + camera.FocalLengthY());
  const ForwardScatterKernel kernel = MakeForwardScatterKernel(scatter.anisotropy_g, focal_px);
  const cv::Mat from_surfaces = backscatter.empty() ? image : cv::Mat(image - backscatter);
  cv::Mat corrected = RemoveForwardScatter(from_surfaces, RangeAlongRays(maps, rays), kernel, scatter.scattering);
  if (!backscatter.empty()) corrected += backscatter;
  const auto level = static_cast<float>(saturation_level);
  for (int row = 0; row < image.rows; ++row) {
    const cv::Vec3f* recorded = image.ptr<cv::Vec3f>(row);
    cv::Vec3f* out = corrected.ptr<cv::Vec3f>(row);
    for (int col = 0; col < image.cols; ++col) {
      const cv::Vec3f& value = recorded[col];
      if (value[0] >= level || value[1] >= level || value[2] >= level) out[col] = value;
    }
  }
  return corrected;
}

}  // namespace lutex
