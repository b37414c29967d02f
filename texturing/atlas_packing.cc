#include "texturing/atlas_packing.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace lutex {

namespace {

// The top outline of what is packed in one page: segments left to right, each at a height.
class Skyline {
 public:
  explicit Skyline(int side) : side_(side), segments_{{0, 0, side}} {}

  // The lowest (then leftmost) position for a w x h rectangle; false when it does not fit.
  bool Find(int width, int height, int* best_x, int* best_y) const {
    int best_top = side_ + 1;
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const int x = segments_[i].x;
      if (x + width > side_) break;
      int y = 0;
      for (std::size_t j = i; j < segments_.size() && segments_[j].x < x + width; ++j) y = std::max(y, segments_[j].y);
      if (y + height <= side_ && y + height < best_top) {
        best_top = y + height;
        *best_x = x;
        *best_y = y;
      }
    }
    return best_top <= side_;
  }

  void Add(int x, int y, int width, int height) {
    std::vector<Segment> updated;
    for (const Segment& s : segments_) {
      const int s_end = s.x + s.width;
      if (s_end <= x || s.x >= x + width) {
        updated.push_back(s);
        continue;
      }
      if (s.x < x) updated.push_back({s.x, s.y, x - s.x});
      if (updated.empty() || updated.back().x + updated.back().width <= x) updated.push_back({x, y + height, width});
      if (s_end > x + width) updated.push_back({x + width, s.y, s_end - (x + width)});
    }
    // Merge neighbours at the same height.
    segments_.clear();
    for (const Segment& s : updated) {
      if (!segments_.empty() && segments_.back().y == s.y) {
        segments_.back().width += s.width;
      } else {
        segments_.push_back(s);
      }
    }
  }

 private:
  struct Segment {
    int x, y, width;
  };
  int side_;
  std::vector<Segment> segments_;
};

// Packs the rectangles in `order` into pages of `side` x `side`, opening pages as needed.
AtlasLayout PackIntoPages(const std::vector<cv::Size>& rectangles, const std::vector<std::size_t>& order, int side) {
  AtlasLayout layout;
  layout.placements.resize(rectangles.size());
  std::vector<Skyline> pages;
  for (std::size_t index : order) {
    const cv::Size& r = rectangles[index];
    AtlasPlacement& placement = layout.placements[index];
    bool placed = false;
    for (std::size_t p = 0; p < pages.size() && !placed; ++p) {
      if (pages[p].Find(r.width, r.height, &placement.x, &placement.y)) {
        placement.page = static_cast<int>(p);
        placed = true;
      }
    }
    if (!placed) {
      pages.emplace_back(side);
      layout.page_sizes.emplace_back(0, 0);
      pages.back().Find(r.width, r.height, &placement.x, &placement.y);
      placement.page = static_cast<int>(pages.size() - 1);
    }
    pages[placement.page].Add(placement.x, placement.y, r.width, r.height);
    cv::Size& used = layout.page_sizes[placement.page];
    used.width = std::max(used.width, placement.x + r.width);
    used.height = std::max(used.height, placement.y + r.height);
  }
  return layout;
}

}  // namespace

AtlasLayout PackAtlas(const std::vector<cv::Size>& rectangles, int max_page_size) {
  double area = 0.0;
  int largest = 1;
  for (std::size_t i = 0; i < rectangles.size(); ++i) {
    const cv::Size& r = rectangles[i];
    if (r.width <= 0 || r.height <= 0 || r.width > max_page_size || r.height > max_page_size) {
      throw std::invalid_argument("atlas: chart " + std::to_string(i) + " is " + std::to_string(r.width) + "x" +
                                  std::to_string(r.height) + " texels, which does not fit a page of " +
                                  std::to_string(max_page_size) + " (use a larger texel size)");
    }
    area += double(r.width) * r.height;
    largest = std::max({largest, r.width, r.height});
  }
  // Skyline packing fills about 85-95 % of a page; start with room for that and grow the page by 10 %
  // until everything fits on one, or the page has its largest size and more pages are needed.
  int side = static_cast<int>(std::ceil(std::sqrt(area / 0.85)));
  side = std::min(max_page_size, std::max(largest, (side + 3) / 4 * 4));
  std::vector<std::size_t> order(rectangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rectangles[a].height != rectangles[b].height ? rectangles[a].height > rectangles[b].height
                                                        : rectangles[a].width > rectangles[b].width;
  });
  AtlasLayout layout = PackIntoPages(rectangles, order, side);
  while (layout.page_sizes.size() > 1 && side < max_page_size) {
    side = std::min(max_page_size, (static_cast<int>(side * 1.1) + 3) / 4 * 4);
    layout = PackIntoPages(rectangles, order, side);
  }
  // Multiples of 4 keep texel rows aligned for image codecs and block-compressed formats.
  for (cv::Size& size : layout.page_sizes) {
    size.width = std::min(max_page_size, (size.width + 3) / 4 * 4);
    size.height = std::min(max_page_size, (size.height + 3) / 4 * 4);
  }
  return layout;
}

}  // namespace lutex
