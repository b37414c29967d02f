#pragma once

// A JPEG with exposure settings in its EXIF block, as a camera writes it, for tests: written by GDAL's
// JPEG driver (real EXIF tags in an APP1 segment, WRITE_EXIF_METADATA), from 8-bit BGR pixels.

#include <filesystem>

#include <opencv2/core.hpp>

namespace lutex::testing {

// `bgr` CV_8UC3. A setting of 0 is left out of the EXIF block. Fails the test (ADD_FAILURE) when GDAL
// cannot write the file.
void WriteExifJpeg(const cv::Mat& bgr, const std::filesystem::path& path, double exposure_time_s, double iso,
                   double f_number);

}  // namespace lutex::testing
