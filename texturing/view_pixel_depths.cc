#include "texturing/view_pixel_depths.h"

#include <algorithm>

namespace lutex {

ViewPixelDepths::ViewPixelDepths(const ViewRaycaster& raycaster, const TextureView& view,
                                 const std::vector<cv::Point>& pixels)
    : width_(static_cast<int>(view.camera.width)) {
  const int height = static_cast<int>(view.camera.height);
  keys_.reserve(pixels.size());
  for (const cv::Point& pixel : pixels) {
    if (pixel.x >= 0 && pixel.y >= 0 && pixel.x < width_ && pixel.y < height) keys_.push_back(Key(pixel.x, pixel.y));
  }
  std::sort(keys_.begin(), keys_.end());
  keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
  std::vector<cv::Point> unique_pixels;
  unique_pixels.reserve(keys_.size());
  for (const std::uint64_t key : keys_) {
    unique_pixels.emplace_back(static_cast<int>(key % static_cast<std::uint64_t>(width_)),
                               static_cast<int>(key / static_cast<std::uint64_t>(width_)));
  }
  raycaster.CastDepths(view, unique_pixels, &depths_);
}

}  // namespace lutex
