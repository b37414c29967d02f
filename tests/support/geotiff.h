#pragma once

// A GeoTIFF read back whole with GDAL, for tests: its samples as float (one channel per band), its
// geotransform and its CRS's EPSG code.

#include <array>
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace lutex::testing {

struct GeoTiff {
  cv::Mat samples;  // CV_32FC(bands), as stored (no scaling)
  std::array<double, 6> geotransform{};
  std::string epsg;  // "32632"; empty without a CRS or an EPSG code
};

// Fails the test (ADD_FAILURE) and returns an empty Mat when the file cannot be read.
GeoTiff ReadGeoTiff(const std::filesystem::path& path);

}  // namespace lutex::testing
