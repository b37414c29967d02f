#include "texturing/texture_fill.h"

#include <cmath>
#include <vector>

namespace lutex {

namespace {

// A level of the pyramid: premultiplied colour and weight (weight 0 = unknown).
struct Level {
  cv::Mat colour;  // CV_32FC3, sum of colour x weight
  cv::Mat weight;  // CV_32F
};

Level Downsample(const Level& fine) {
  Level coarse;
  const int rows = (fine.colour.rows + 1) / 2, cols = (fine.colour.cols + 1) / 2;
  coarse.colour = cv::Mat(rows, cols, CV_32FC3, cv::Scalar::all(0));
  coarse.weight = cv::Mat(rows, cols, CV_32F, cv::Scalar(0));
  for (int row = 0; row < fine.colour.rows; ++row) {
    for (int col = 0; col < fine.colour.cols; ++col) {
      coarse.colour.at<cv::Vec3f>(row / 2, col / 2) += fine.colour.at<cv::Vec3f>(row, col);
      coarse.weight.at<float>(row / 2, col / 2) += fine.weight.at<float>(row, col);
    }
  }
  // Normalise so a level's weights stay in [0, 1] (a block fully known has weight 1).
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const float w = coarse.weight.at<float>(row, col);
      if (w > 0.0f) {
        coarse.colour.at<cv::Vec3f>(row, col) *= std::min(1.0f, w) / w;
        coarse.weight.at<float>(row, col) = std::min(1.0f, w);
      }
    }
  }
  return coarse;
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

void FillUnknownTexels(cv::Mat& page) {
  CV_Assert(page.type() == CV_32FC3);
  std::vector<Level> pyramid(1);
  pyramid[0].colour = cv::Mat(page.size(), CV_32FC3, cv::Scalar::all(0));
  pyramid[0].weight = cv::Mat(page.size(), CV_32F, cv::Scalar(0));
  bool any_known = false;
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      const cv::Vec3f& value = page.at<cv::Vec3f>(row, col);
      if (std::isnan(value[0])) continue;
      pyramid[0].colour.at<cv::Vec3f>(row, col) = value;
      pyramid[0].weight.at<float>(row, col) = 1.0f;
      any_known = true;
    }
  }
  if (!any_known) {
    page.setTo(cv::Scalar::all(0));
    return;
  }
  while (pyramid.back().colour.rows > 1 || pyramid.back().colour.cols > 1) pyramid.push_back(Downsample(pyramid.back()));
  // Push: from the coarsest level down, blend each level's own colour (by its weight) with the level above.
  for (std::size_t level = pyramid.size() - 1; level-- > 0;) {
    Level& fine = pyramid[level];
    const Level& coarse = pyramid[level + 1];
    for (int row = 0; row < fine.colour.rows; ++row) {
      for (int col = 0; col < fine.colour.cols; ++col) {
        float& w = fine.weight.at<float>(row, col);
        if (w >= 1.0f) continue;
        const cv::Vec3f own = fine.colour.at<cv::Vec3f>(row, col);  // premultiplied
        fine.colour.at<cv::Vec3f>(row, col) = own + (1.0f - w) * SampleCoarse(coarse, row, col);
        w = 1.0f;
      }
    }
  }
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      cv::Vec3f& value = page.at<cv::Vec3f>(row, col);
      if (std::isnan(value[0])) value = pyramid[0].colour.at<cv::Vec3f>(row, col);
    }
  }
}

}  // namespace lutex
