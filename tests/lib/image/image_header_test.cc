// Image headers read without decoding: PNG (8 and 16 bit, grey and colour) and JPEG give their size,
// channels and depth; other files are left to the decoder; a truncated header is an error naming the file.

#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "lib/image/image_header.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

TEST(ImageHeader, PngAndJpegTellTheirSizeChannelsAndDepth) {
  testing::TempDir dir;
  cv::imwrite((dir.path() / "a.png").string(), cv::Mat(30, 40, CV_16UC3, cv::Scalar::all(7)));
  cv::imwrite((dir.path() / "b.png").string(), cv::Mat(5, 6, CV_8UC1, cv::Scalar::all(7)));
  cv::imwrite((dir.path() / "c.jpg").string(), cv::Mat(33, 44, CV_8UC3, cv::Scalar::all(7)));
  const auto a = ReadImageHeader(dir.path() / "a.png");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->format, "PNG");
  EXPECT_EQ(a->width, 40);
  EXPECT_EQ(a->height, 30);
  EXPECT_EQ(a->channels, 3);
  EXPECT_EQ(a->bits_per_sample, 16);
  const auto b = ReadImageHeader(dir.path() / "b.png");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->channels, 1);
  EXPECT_EQ(b->bits_per_sample, 8);
  const auto c = ReadImageHeader(dir.path() / "c.jpg");
  ASSERT_TRUE(c);
  EXPECT_EQ(c->format, "JPEG");
  EXPECT_EQ(c->width, 44);
  EXPECT_EQ(c->height, 33);
  EXPECT_EQ(c->channels, 3);
  EXPECT_EQ(c->bits_per_sample, 8);
  // A JPEG named .png is read by its signature.
  fs::copy_file(dir.path() / "c.jpg", dir.path() / "d.png");
  EXPECT_EQ(ReadImageHeader(dir.path() / "d.png")->format, "JPEG");

  EXPECT_NO_THROW(CheckImageHeader(dir.path() / "a.png", 40, 30, ImageEncoding::kLinear16));
  EXPECT_NO_THROW(CheckImageHeader(dir.path() / "c.jpg", 44, 33, ImageEncoding::kSrgb8));
  EXPECT_THROW(CheckImageHeader(dir.path() / "a.png", 40, 30, ImageEncoding::kSrgb8), std::runtime_error);
  EXPECT_THROW(CheckImageHeader(dir.path() / "a.png", 41, 30, ImageEncoding::kLinear16), std::runtime_error);
  EXPECT_THROW(CheckImageHeader(dir.path() / "c.jpg", 44, 33, ImageEncoding::kFloat), std::runtime_error);
}

TEST(ImageHeader, OtherFilesAreLeftToTheDecoderAndTruncatedHeadersAreErrors) {
  testing::TempDir dir;
  // A TIFF signature ("II*\0"): a decoder recognises it, so its pixels are left to decoding.
  std::ofstream(dir.path() / "notes.tif").write("II*\0 not really", 15);
  EXPECT_FALSE(ReadImageHeader(dir.path() / "notes.tif"));
  EXPECT_NO_THROW(CheckImageHeader(dir.path() / "notes.tif", 1, 1, ImageEncoding::kSrgb8));
  // No decoder recognises these first bytes: refused before anything is decoded or written.
  std::ofstream(dir.path() / "notes.png") << "GIF89a, or not";
  try {
    CheckImageHeader(dir.path() / "notes.png", 1, 1, ImageEncoding::kSrgb8);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), (dir.path() / "notes.png").string() +
                                             ": not an image (its first bytes match no image format lutex reads)");
  }
  cv::imwrite((dir.path() / "a.png").string(), cv::Mat(30, 40, CV_16UC3, cv::Scalar::all(7)));
  fs::resize_file(dir.path() / "a.png", 20);
  try {
    ReadImageHeader(dir.path() / "a.png");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), (dir.path() / "a.png").string() + ": not a readable PNG image (truncated header)");
  }
  cv::imwrite((dir.path() / "c.jpg").string(), cv::Mat(33, 44, CV_8UC3, cv::Scalar::all(7)));
  fs::resize_file(dir.path() / "c.jpg", 4);
  EXPECT_THROW(ReadImageHeader(dir.path() / "c.jpg"), std::runtime_error);
  EXPECT_THROW(ReadImageHeader(dir.path() / "missing.png"), std::runtime_error);
}

}  // namespace
}  // namespace lutex
