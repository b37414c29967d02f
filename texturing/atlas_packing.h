#pragma once

// Packs rectangles (texture charts) into as few atlas pages as it can: skyline bottom-left packing
// (Jylanki 2010, "A Thousand Ways to Pack the Bin"), rectangles placed tallest first. Pages are square
// of a side chosen from the total area (at most `max_page_size`) and cropped to what they use.

#include <vector>

#include <opencv2/core.hpp>

namespace lutex {

struct AtlasPlacement {
  int page = 0;
  int x = 0;  // top-left corner in the page, texels
  int y = 0;
};

struct AtlasLayout {
  std::vector<AtlasPlacement> placements;  // one per rectangle, in input order
  std::vector<cv::Size> page_sizes;
};

// Throws std::invalid_argument when a rectangle is larger than `max_page_size` or not positive.
AtlasLayout PackAtlas(const std::vector<cv::Size>& rectangles, int max_page_size);

}  // namespace lutex
