#include "tests/support/exif_jpeg.h"

#include <string>

#include <gdal.h>
#include <gtest/gtest.h>

namespace lutex::testing {

void WriteExifJpeg(const cv::Mat& bgr, const std::filesystem::path& path, double exposure_time_s, double iso,
                   double f_number) {
  GDALAllRegister();
  GDALDatasetH memory = GDALCreate(GDALGetDriverByName("MEM"), "", bgr.cols, bgr.rows, 3, GDT_Byte, nullptr);
  for (int band = 0; band < 3; ++band) {
    cv::Mat channel;
    cv::extractChannel(bgr, channel, 2 - band);  // RGB bands from BGR
    if (GDALRasterIO(GDALGetRasterBand(memory, band + 1), GF_Write, 0, 0, bgr.cols, bgr.rows, channel.data, bgr.cols,
                     bgr.rows, GDT_Byte, 0, 0) != CE_None) {
      ADD_FAILURE() << "GDAL could not fill the bands of " << path;
    }
  }
  // GDAL's EXIF text: rationals in parentheses, counts plain.
  if (exposure_time_s > 0) GDALSetMetadataItem(memory, "EXIF_ExposureTime", ("(" + std::to_string(exposure_time_s) + ")").c_str(), nullptr);
  if (iso > 0) GDALSetMetadataItem(memory, "EXIF_ISOSpeedRatings", std::to_string(static_cast<int>(iso)).c_str(), nullptr);
  if (f_number > 0) GDALSetMetadataItem(memory, "EXIF_FNumber", ("(" + std::to_string(f_number) + ")").c_str(), nullptr);
  const char* options[] = {"QUALITY=100", "WRITE_EXIF_METADATA=YES", nullptr};
  GDALDatasetH jpeg = GDALCreateCopy(GDALGetDriverByName("JPEG"), path.c_str(), memory, FALSE,
                                     const_cast<char**>(options), nullptr, nullptr);
  if (jpeg == nullptr) ADD_FAILURE() << "GDAL could not write " << path;
  else GDALClose(jpeg);
  GDALClose(memory);
}

}  // namespace lutex::testing
