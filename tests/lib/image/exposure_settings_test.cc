#include "lib/image/exposure_settings.h"

#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/exif_jpeg.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

TEST(ExposureSettings, ReadsTheExifTagsOfAJpegAsACameraWritesThem) {
  testing::TempDir dir;
  const cv::Mat pixels(24, 32, CV_8UC3, cv::Scalar(40, 90, 160));
  testing::WriteExifJpeg(pixels, dir.path() / "a.jpg", 1.0 / 125, 400, 5.6);
  const ExposureSettings settings = ReadExposureSettings(dir.path() / "a.jpg");
  EXPECT_NEAR(settings.exposure_time_s, 0.008, 1e-6);
  EXPECT_EQ(settings.iso, 400);
  EXPECT_NEAR(settings.f_number, 5.6, 1e-6);
  // No .aux.xml or other file appears beside the image.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(ExposureSettings, ImagesWithoutExifHaveNone) {
  testing::TempDir dir;
  const cv::Mat pixels(24, 32, CV_8UC3, cv::Scalar(40, 90, 160));
  cv::imwrite((dir.path() / "plain.png").string(), pixels);
  cv::imwrite((dir.path() / "plain.jpg").string(), pixels);
  std::ofstream(dir.path() / "not_an_image.jpg") << "hello";
  for (const char* name : {"plain.png", "plain.jpg", "not_an_image.jpg"}) {
    const ExposureSettings settings = ReadExposureSettings(dir.path() / name);
    EXPECT_EQ(settings.exposure_time_s, 0.0) << name;
    EXPECT_EQ(settings.iso, 0.0) << name;
    EXPECT_EQ(settings.f_number, 0.0) << name;
  }
  EXPECT_THROW(ReadExposureSettings(dir.path() / "missing.jpg"), std::runtime_error);
}

TEST(ExposureSettings, TheProductUsesTheFactorsEveryImageHas) {
  ExposureSettings a{0.01, 200, 4.0}, b{0.02, 0, 2.0};
  const ExposureFactors factors = FactorsInEvery({a, b});
  EXPECT_TRUE(factors.exposure_time);
  EXPECT_FALSE(factors.iso);
  EXPECT_TRUE(factors.f_number);
  EXPECT_DOUBLE_EQ(ExposureProduct(a, factors), 0.01 / 16);
  EXPECT_DOUBLE_EQ(ExposureProduct(b, factors), 0.02 / 4);
  // Twice the time, twice the ISO, one stop wider (N / sqrt 2): 8 times the light.
  const ExposureFactors all{true, true, true};
  EXPECT_NEAR(ExposureProduct({0.02, 400, 4.0 / std::sqrt(2.0)}, all) / ExposureProduct(a, all), 8.0, 1e-12);
  EXPECT_EQ(ExposureProduct(ExposureSettings{0.01, 0, 4.0}, all), 0.0);  // lacks the ISO the factors use
  EXPECT_FALSE(FactorsInEvery({}).Any());
  EXPECT_EQ(ExposureProduct(a, ExposureFactors{}), 1.0);
}

}  // namespace
}  // namespace lutex
