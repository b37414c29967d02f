#include "lib/image/image_io.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(ImageIo, SrgbTransferMatchesTheStandard) {
  EXPECT_NEAR(SrgbToLinear(0.5), 0.214041, 1e-6);  // IEC 61966-2-1
  EXPECT_NEAR(LinearToSrgb(0.0031308), 0.04045, 1e-5);
  for (double v = 0.0; v <= 1.0; v += 0.01) EXPECT_NEAR(SrgbToLinear(LinearToSrgb(v)), v, 1e-12);
}

cv::Mat Ramp() {
  cv::Mat image(4, 256, CV_32FC3);
  for (int col = 0; col < 256; ++col) {
    for (int row = 0; row < 4; ++row) {
      const float v = static_cast<float>(col) / 255.0f;
      image.at<cv::Vec3f>(row, col) = cv::Vec3f(v, 0.5f * v, 1.0f - v);
    }
  }
  return image;
}

// 16-bit linear keeps values to half a code (1/131070); 8-bit sRGB to half an sRGB code, which is at
// most 0.5/255 * dlinear/dsrgb <= 0.0054 in linear terms (at the bright end).
TEST(ImageIo, EncodingRoundTrips) {
  testing::TempDir dir;
  const cv::Mat ramp = Ramp();
  WriteLinearImage(ramp, dir.path() / "a.png", ImageEncoding::kLinear16);
  EXPECT_LT(cv::norm(ReadLinearImage(dir.path() / "a.png", ImageEncoding::kLinear16), ramp, cv::NORM_INF), 1.0 / 131070 + 1e-7);
  WriteLinearImage(ramp, dir.path() / "b.png", ImageEncoding::kSrgb8);
  EXPECT_LT(cv::norm(ReadLinearImage(dir.path() / "b.png", ImageEncoding::kSrgb8), ramp, cv::NORM_INF), 0.0055);
  // Channel order: red is stored in OpenCV's third channel.
  const cv::Mat stored = cv::imread((dir.path() / "a.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(stored.at<cv::Vec3w>(0, 255)[2], 65535);
  EXPECT_EQ(stored.at<cv::Vec3w>(0, 255)[0], 0);
}

// NaN (a pixel without albedo) encodes as 0 in every encoding, values outside [0, 1] saturate in the
// integer encodings and stay in float, and red goes to OpenCV's third channel.
TEST(ImageIo, EncodingHandlesNanAndOutOfRangeValues) {
  const float nan = std::nanf("");
  cv::Mat values(1, 3, CV_32FC3);
  values.at<cv::Vec3f>(0, 0) = cv::Vec3f(nan, 0.25f, nan);
  values.at<cv::Vec3f>(0, 1) = cv::Vec3f(-0.5f, 2.0f, 1.0f);
  values.at<cv::Vec3f>(0, 2) = cv::Vec3f(1.0f, 0.0f, 0.5f);
  const cv::Mat srgb = EncodeLinearImage(values, ImageEncoding::kSrgb8);
  EXPECT_EQ(srgb.at<cv::Vec3b>(0, 0), cv::Vec3b(0, static_cast<uchar>(std::lround(255 * LinearToSrgb(0.25))), 0));
  EXPECT_EQ(srgb.at<cv::Vec3b>(0, 1), cv::Vec3b(255, 255, 0));
  EXPECT_EQ(srgb.at<cv::Vec3b>(0, 2), cv::Vec3b(static_cast<uchar>(std::lround(255 * LinearToSrgb(0.5))), 0, 255));
  const cv::Mat linear16 = EncodeLinearImage(values, ImageEncoding::kLinear16);
  EXPECT_EQ(linear16.at<cv::Vec3w>(0, 0), cv::Vec3w(0, 16384, 0));
  EXPECT_EQ(linear16.at<cv::Vec3w>(0, 1), cv::Vec3w(65535, 65535, 0));
  EXPECT_EQ(linear16.at<cv::Vec3w>(0, 2), cv::Vec3w(32768, 0, 65535));
  const cv::Mat as_float = EncodeLinearImage(values, ImageEncoding::kFloat);
  EXPECT_EQ(as_float.at<cv::Vec3f>(0, 0), cv::Vec3f(0.0f, 0.25f, 0.0f));
  EXPECT_EQ(as_float.at<cv::Vec3f>(0, 1), cv::Vec3f(1.0f, 2.0f, -0.5f));
}

// The fast 8-bit encoder gives exactly round(255 * LinearToSrgb(v)) for values dense in [0, 1].
TEST(ImageIo, FastSrgbEncodingIsExact) {
  cv::Mat values(1, 200001, CV_32FC3);
  for (int i = 0; i < values.cols; ++i) {
    const float v = static_cast<float>(i) / 200000.0f;
    values.at<cv::Vec3f>(0, i) = cv::Vec3f(v, v, v);
  }
  const cv::Mat encoded = EncodeLinearImage(values, ImageEncoding::kSrgb8);
  int mismatches = 0;
  for (int i = 0; i < values.cols; ++i) {
    const double v = values.at<cv::Vec3f>(0, i)[0];
    mismatches += encoded.at<cv::Vec3b>(0, i)[0] != static_cast<int>(std::lround(255.0 * LinearToSrgb(v)));
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(ImageIo, WrongEncodingAndMissingFilesAreErrors) {
  testing::TempDir dir;
  WriteLinearImage(Ramp(), dir.path() / "eight.png", ImageEncoding::kSrgb8);
  EXPECT_THROW(ReadLinearImage(dir.path() / "eight.png", ImageEncoding::kLinear16), std::runtime_error);
  EXPECT_THROW(ReadLinearImage(dir.path() / "missing.png", ImageEncoding::kSrgb8), std::runtime_error);
  std::ofstream(dir.path() / "broken.png") << "not a png";
  EXPECT_THROW(ReadLinearImage(dir.path() / "broken.png", ImageEncoding::kSrgb8), std::runtime_error);
}

}  // namespace
}  // namespace lutex
