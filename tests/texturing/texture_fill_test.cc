// The pull-push fill of unknown texels on pages whose known texels are placed by hand: a page of one
// colour stays that colour everywhere (also from one texel in a page's last row and column), the texels
// between two charts take colours between theirs, and the rows filled on two threads equal the rows
// filled on one (a race between rows would show).

#include "texturing/texture_fill.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace lutex {
namespace {

constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();

cv::Mat UnknownPage(int rows, int cols) { return cv::Mat(rows, cols, CV_32FC3, cv::Scalar::all(kUnknown)); }

void ExpectEveryTexelIs(const cv::Mat& page, const cv::Vec3f& colour) {
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(page.at<cv::Vec3f>(row, col)[c], colour[c], 1e-5) << row << " " << col;
    }
  }
}

TEST(FillUnknownTexels, TexelsAroundOneColourTakeThatColour) {
  cv::Mat page = UnknownPage(37, 53);  // odd sizes: pyramid levels with a half block at the edge
  const cv::Vec3f colour(0.2f, 0.5f, 0.8f);
  page(cv::Rect(10, 7, 9, 6)).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
  page(cv::Rect(40, 25, 3, 11)).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
  FillUnknownTexels(page, 2);
  ExpectEveryTexelIs(page, colour);
}

TEST(FillUnknownTexels, OneTexelInTheLastRowAndColumnOfAnOddPageColoursTheWholePage) {
  // Each pyramid level of a 37 x 53 page ends in a half block: the texel reaches the top only if every
  // level keeps its last row and column.
  cv::Mat page = UnknownPage(37, 53);
  const cv::Vec3f colour(0.9f, 0.3f, 0.6f);
  page.at<cv::Vec3f>(36, 52) = colour;
  FillUnknownTexels(page, 2);
  ExpectEveryTexelIs(page, colour);
}

TEST(FillUnknownTexels, TexelsBetweenTwoChartsTakeColoursBetweenTheirsNearestTheNearerOne) {
  cv::Mat page = UnknownPage(16, 64);
  page(cv::Rect(0, 0, 8, 16)).setTo(cv::Scalar::all(0.0));
  page(cv::Rect(56, 0, 8, 16)).setTo(cv::Scalar::all(1.0));
  FillUnknownTexels(page, 2);
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 8; col < 56; ++col) {
      const float value = page.at<cv::Vec3f>(row, col)[0];
      ASSERT_GE(value, 0.0f);
      ASSERT_LE(value, 1.0f);
    }
    EXPECT_LT(page.at<cv::Vec3f>(row, 9)[0], 0.25f);
    EXPECT_GT(page.at<cv::Vec3f>(row, 54)[0], 0.75f);
  }
}

TEST(FillUnknownTexels, APageWithNothingKnownIsBlackAndOneFullyKnownIsUntouched) {
  cv::Mat unknown = UnknownPage(5, 7);
  FillUnknownTexels(unknown, 2);
  EXPECT_EQ(cv::countNonZero(unknown.reshape(1)), 0);
  cv::Mat known(5, 7, CV_32FC3, cv::Scalar(0.1, 0.2, 0.3));
  const cv::Mat before = known.clone();
  FillUnknownTexels(known, 2);
  EXPECT_EQ(cv::norm(known, before, cv::NORM_INF), 0.0);
}

TEST(FillUnknownTexels, TwoThreadsFillEveryTexelAsOneDoes) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  cv::Mat page = UnknownPage(301, 257);
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      if (value(random) < 0.3f) page.at<cv::Vec3f>(row, col) = cv::Vec3f(value(random), value(random), value(random));
    }
  }
  cv::Mat one = page.clone(), two = page.clone();
  FillUnknownTexels(one, 1);
  FillUnknownTexels(two, 2);
  EXPECT_EQ(cv::countNonZero(cv::Mat(one != two).reshape(1)), 0);
  for (int row = 0; row < page.rows; ++row) {
    for (int col = 0; col < page.cols; ++col) {
      const cv::Vec3f& known = page.at<cv::Vec3f>(row, col);
      if (!std::isnan(known[0])) {
        ASSERT_EQ(two.at<cv::Vec3f>(row, col), known);
      }
      ASSERT_FALSE(std::isnan(two.at<cv::Vec3f>(row, col)[0]));
    }
  }
}

}  // namespace
}  // namespace lutex
