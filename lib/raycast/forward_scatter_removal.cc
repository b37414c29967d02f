#include "lib/raycast/forward_scatter_removal.h"

#include <cmath>
#include <limits>
#include <stdexcept>

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

cv::Mat WithoutForwardScatter(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                              const ForwardScatter& scatter) {
  if (scatter.IsNone()) return image;
  const Camera& camera = rays.camera();
  const double focal_px = 0.5 * (camera.FocalLengthX() + camera.FocalLengthY());
  return RemoveForwardScatter(image, RangeAlongRays(maps, rays),
                              MakeForwardScatterKernel(scatter.anisotropy_g, focal_px), scatter.scattering);
}

}  // namespace lutex
