#include "lib/calibration/exposure_record.h"

#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

TEST(ExposureRecord, WrittenAndReadBackTheSame) {
  testing::TempDir dir;
  ExposureRecord record;
  record.exif_factors = {true, false, true};
  record.exif_reference = 0.0005;
  record.fitted_gains = {{"dive/a.jpg", 0.93}, {"b.jpg", 1.07}};
  record.fitted_images = "/surveys/dive 7/images";
  WriteExposureRecord(record, dir.path() / "exposure.json");
  const ExposureRecord back = ReadExposureRecord(dir.path() / "exposure.json");
  EXPECT_TRUE(back.exif_factors.exposure_time);
  EXPECT_FALSE(back.exif_factors.iso);
  EXPECT_TRUE(back.exif_factors.f_number);
  EXPECT_EQ(back.exif_reference, 0.0005);
  EXPECT_EQ(back.fitted_gains, record.fitted_gains);
  EXPECT_EQ(back.fitted_images, record.fitted_images);
  // Without EXIF: the reference is null, and an image's gain is its fitted one when it is in the fitted
  // images' folder (another dive's a.png is another image), else 1.
  fs::create_directories(dir.path() / "images");
  fs::create_directories(dir.path() / "other_dive");
  WriteExposureRecord(ExposureRecord{{}, 0.0, {{"a.png", 1.1}}, dir.path() / "images"}, dir.path() / "plain.json");
  const ExposureRecord plain = ReadExposureRecord(dir.path() / "plain.json");
  EXPECT_EQ(plain.exif_reference, 0.0);
  EXPECT_EQ(plain.GainOf(dir.path() / "images", "a.png"), 1.1);
  EXPECT_EQ(plain.GainOf(dir.path() / "images" / ".", "a.png"), 1.1);
  EXPECT_EQ(plain.GainOf(dir.path() / "images", "other.png"), 1.0);
  EXPECT_EQ(plain.GainOf(dir.path() / "other_dive", "a.png"), 1.0);
  EXPECT_FALSE(plain.HasGainsFor(dir.path() / "other_dive"));
}

TEST(ExposureRecord, BadFilesNameTheFileAndTheProblem) {
  testing::TempDir dir;
  const auto error_of = [&](const std::string& text) {
    std::ofstream(dir.path() / "exposure.json") << text;
    try {
      ReadExposureRecord(dir.path() / "exposure.json");
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string path = (dir.path() / "exposure.json").string();
  EXPECT_EQ(error_of(R"({"fitted_gains": {"a.png": -1}})"), path + ": fitted_gains.a.png must be positive");
  EXPECT_EQ(error_of(R"({"fitted_gains": [1, 2]})"), path + ": fitted_gains must be an object of image names");
  EXPECT_EQ(error_of(R"({"exif": {"reference": 0}})"), path + ": exif.reference must be positive");
  EXPECT_NE(error_of(R"({"gains": {}})").find("gains"), std::string::npos);
  EXPECT_NE(error_of("{").find("not valid JSON"), std::string::npos);
  EXPECT_THROW(ReadExposureRecord(dir.path() / "missing.json"), std::runtime_error);
}

}  // namespace
}  // namespace lutex
