#include "texturing/atlas_packing.h"

#include <random>

#include <gtest/gtest.h>

namespace lutex {
namespace {

// Every rectangle inside its page and no two on one page overlapping.
void ExpectValidLayout(const std::vector<cv::Size>& rectangles, const AtlasLayout& layout, int max_page_size) {
  ASSERT_EQ(layout.placements.size(), rectangles.size());
  for (const cv::Size& page : layout.page_sizes) {
    EXPECT_LE(page.width, max_page_size);
    EXPECT_LE(page.height, max_page_size);
  }
  for (std::size_t i = 0; i < rectangles.size(); ++i) {
    const AtlasPlacement& a = layout.placements[i];
    ASSERT_GE(a.page, 0);
    ASSERT_LT(a.page, static_cast<int>(layout.page_sizes.size()));
    const cv::Rect ra(a.x, a.y, rectangles[i].width, rectangles[i].height);
    EXPECT_GE(ra.x, 0);
    EXPECT_GE(ra.y, 0);
    EXPECT_LE(ra.x + ra.width, layout.page_sizes[a.page].width);
    EXPECT_LE(ra.y + ra.height, layout.page_sizes[a.page].height);
    for (std::size_t j = i + 1; j < rectangles.size(); ++j) {
      const AtlasPlacement& b = layout.placements[j];
      if (a.page != b.page) continue;
      const cv::Rect rb(b.x, b.y, rectangles[j].width, rectangles[j].height);
      EXPECT_EQ((ra & rb).area(), 0) << "rectangles " << i << " and " << j << " overlap";
    }
  }
}

TEST(AtlasPacking, RandomChartsFitOnePageWithoutOverlapAndFillMostOfIt) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> side(1, 60);
  std::vector<cv::Size> rectangles;
  double area = 0.0;
  for (int i = 0; i < 300; ++i) {
    rectangles.emplace_back(side(random), side(random));
    area += rectangles.back().area();
  }
  const AtlasLayout layout = PackAtlas(rectangles, 8192);
  ExpectValidLayout(rectangles, layout, 8192);
  ASSERT_EQ(layout.page_sizes.size(), 1u);
  // Skyline packing of mixed rectangles, tallest first, fills well over half of the page.
  EXPECT_GT(area / layout.page_sizes[0].area(), 0.7);
}

TEST(AtlasPacking, OpensMorePagesWhenOneIsFull) {
  const std::vector<cv::Size> rectangles(10, cv::Size(100, 100));
  const AtlasLayout layout = PackAtlas(rectangles, 256);  // four 100 x 100 per 256 x 256 page
  ExpectValidLayout(rectangles, layout, 256);
  EXPECT_EQ(layout.page_sizes.size(), 3u);
}

TEST(AtlasPacking, RejectsAChartLargerThanAPage) {
  EXPECT_THROW(PackAtlas({cv::Size(10, 10), cv::Size(300, 20)}, 256), std::invalid_argument);
  EXPECT_THROW(PackAtlas({cv::Size(0, 10)}, 256), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
