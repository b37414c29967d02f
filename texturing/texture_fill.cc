#include "texturing/texture_fill.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "lib/util/parallel_for.h"

namespace lutex {

namespace {

// A level of the pyramid: premultiplied colour and weight (weight 0 = unknown).
struct Level {
  cv::Mat colour;  // CV_32FC3, sum of colour x weight
  cv::Mat weight;  // CV_32F
};

// The next coarser level of a fine level `rows` x `cols` whose texel (row, col) has premultiplied colour
// and weight `fine_texel(row, col)`. Coarse rows are made in parallel, each from its own two fine rows.
template <typename FineTexel>
Level Downsample(int fine_rows, int fine_cols, FineTexel fine_texel, int num_threads) {
  Level coarse;
  const int rows = (fine_rows + 1) / 2, cols = (fine_cols + 1) / 2;
  coarse.colour = cv::Mat(rows, cols, CV_32FC3, cv::Scalar::all(0));
  coarse.weight = cv::Mat(rows, cols, CV_32F, cv::Scalar(0));
  ParallelFor(static_cast<std::size_t>(rows), num_threads, [&](std::size_t coarse_row) {
    const int row = static_cast<int>(coarse_row);
    auto* colour = coarse.colour.ptr<cv::Vec3f>(row);
    auto* weight = coarse.weight.ptr<float>(row);
    for (int fine_row = 2 * row; fine_row < std::min(2 * row + 2, fine_rows); ++fine_row) {
      for (int col = 0; col < fine_cols; ++col) {
        const auto [texel_colour, texel_weight] = fine_texel(fine_row, col);
        colour[col / 2] += texel_colour;
        weight[col / 2] += texel_weight;
      }
    }
    // Normalise so a level's weights stay in [0, 1] (a block fully known has weight 1).
    for (int col = 0; col < cols; ++col) {
      const float w = weight[col];
      if (w > 0.0f) {
        colour[col] *= std::min(1.0f, w) / w;
        weight[col] = std::min(1.0f, w);
      }
    }
  });
  return coarse;
}

Level Downsample(const Level& fine, int num_threads) {
  return Downsample(
      fine.colour.rows, fine.colour.cols,
      [&fine](int row, int col) {
        return std::pair<cv::Vec3f, float>(fine.colour.at<cv::Vec3f>(row, col), fine.weight.at<float>(row, col));
      },
      num_threads);
}

// Bilinear sample of a coarse level's normalised colour at the centre of fine texel (row, col).
cv::Vec3f SampleCoarse(const Level& coarse, int row, int col) {
  const float y = (float(row) + 0.5f) / 2.0f - 0.5f, x = (float(col) + 0.5f) / 2.0f - 0.5f;
  const int y0 = static_cast<int>(std::floor(y)), x0 = static_cast<int>(std::floor(x));
  cv::Vec3f sum(0, 0, 0);
  float weight = 0.0f;
  for (int dy = 0; dy <= 1; ++dy) {
    for (int dx = 0; dx <= 1; ++dx) {
      const int r = std::min(std::max(y0 + dy, 0), coarse.colour.rows - 1);
      const int c = std::min(std::max(x0 + dx, 0), coarse.colour.cols - 1);
      const float fy = y - float(y0), fx = x - float(x0);
      const float w = (dy ? fy : 1.0f - fy) * (dx ? fx : 1.0f - fx) * coarse.weight.at<float>(r, c);
      sum += w * coarse.colour.at<cv::Vec3f>(r, c) / std::max(coarse.weight.at<float>(r, c), 1e-20f);
      weight += w;
    }
  }
  return weight > 0.0f ? sum / weight : sum;
}

}  // namespace

void FillUnknownTexels(cv::Mat& page, int num_threads) {
  CV_Assert(page.type() == CV_32FC3);
  // The page itself is the finest level (a known texel has weight 1, an unknown one 0), so the pyramid
  // costs a third of the page, not a copy of it.
  bool any_known = false, any_unknown = false;
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      (std::isnan(page.at<cv::Vec3f>(row, col)[0]) ? any_unknown : any_known) = true;
    }
  }
  if (!any_known) {
    page.setTo(cv::Scalar::all(0));
    return;
  }
  if (!any_unknown) return;
  std::vector<Level> pyramid;
  pyramid.push_back(Downsample(
      page.rows, page.cols,
      [&page](int row, int col) {
        const cv::Vec3f& value = page.at<cv::Vec3f>(row, col);
        return std::isnan(value[0]) ? std::pair<cv::Vec3f, float>(cv::Vec3f(0, 0, 0), 0.0f)
                                    : std::pair<cv::Vec3f, float>(value, 1.0f);
      },
      num_threads));
  while (pyramid.back().colour.rows > 1 || pyramid.back().colour.cols > 1) {
    pyramid.push_back(Downsample(pyramid.back(), num_threads));
  }
  // Push: from the coarsest level down, blend each level's own colour (by its weight) with the level above.
  for (std::size_t level = pyramid.size() - 1; level-- > 0;) {
    Level& fine = pyramid[level];
    const Level& coarse = pyramid[level + 1];
    ParallelFor(static_cast<std::size_t>(fine.colour.rows), num_threads, [&](std::size_t fine_row) {
      const int row = static_cast<int>(fine_row);
      for (int col = 0; col < fine.colour.cols; ++col) {
        float& w = fine.weight.at<float>(row, col);
        if (w >= 1.0f) continue;
        const cv::Vec3f own = fine.colour.at<cv::Vec3f>(row, col);  // premultiplied
        fine.colour.at<cv::Vec3f>(row, col) = own + (1.0f - w) * SampleCoarse(coarse, row, col);
        w = 1.0f;
      }
    });
  }
  // The page's unknown texels (weight 0) take the level above's colour.
  ParallelFor(static_cast<std::size_t>(page.rows), num_threads, [&](std::size_t page_row) {
    const int row = static_cast<int>(page_row);
    for (int col = 0; col < page.cols; ++col) {
      cv::Vec3f& value = page.at<cv::Vec3f>(row, col);
      if (std::isnan(value[0])) value = SampleCoarse(pyramid[0], row, col);
    }
  });
}

}  // namespace lutex
