#pragma once

// The ray-cast depth of the pixels a view is sampled at, in one of two forms behind one lookup:
//   - a rendered window of the view (GeometryMaps: every pixel of a rectangle, adaptive casting), for
//     samples that cover their rectangle (a chart's texels);
//   - only the listed pixels, each cast, for samples that are few and scattered over the image (seam
//     points: their rectangle is most of a 12 MP view, of which they read a few percent).
// Both give the planar depth of the pixel's ray (GeometryMaps::depth), equal to float precision.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "lib/raycast/geometry_maps.h"
#include "texturing/texture_views.h"

namespace lutex {

class ViewPixelDepths {
 public:
  // The depths of a rendered window; `maps` must outlive this.
  explicit ViewPixelDepths(const GeometryMaps& maps) : maps_(&maps) {}

  // The depths of `pixels` of `view` (image coordinates, any order, repeats allowed), cast now on the
  // calling thread.
  ViewPixelDepths(const ViewRaycaster& raycaster, const TextureView& view, const std::vector<cv::Point>& pixels);

  // The depth at image pixel (col, row) into `depth` (NaN where the ray hits nothing); false when that
  // pixel was neither rendered nor cast.
  bool At(int col, int row, float* depth) const {
    if (maps_) {
      const int map_col = col - maps_->origin.x, map_row = row - maps_->origin.y;
      if (map_col < 0 || map_row < 0 || map_col >= maps_->depth.cols || map_row >= maps_->depth.rows) return false;
      *depth = maps_->depth.at<float>(map_row, map_col);
      return true;
    }
    if (col < 0 || row < 0 || col >= width_) return false;
    const std::uint64_t key = Key(col, row);
    const auto found = std::lower_bound(keys_.begin(), keys_.end(), key);
    if (found == keys_.end() || *found != key) return false;
    *depth = depths_[static_cast<std::size_t>(found - keys_.begin())];
    return true;
  }

 private:
  std::uint64_t Key(int col, int row) const {
    return static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(width_) + static_cast<std::uint64_t>(col);
  }

  const GeometryMaps* maps_ = nullptr;
  int width_ = 0;
  std::vector<std::uint64_t> keys_;  // of the cast pixels, ascending
  std::vector<float> depths_;        // of keys_
};

}  // namespace lutex
