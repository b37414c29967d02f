#pragma once

// A GeoTIFF (or any raster GDAL reads) read back small, for previews: at most `max_side` pixels on its
// longer side, from its overviews when it has them (a COG's are made for this), with its grid.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "lib/geo/cog_writer.h"

namespace lutex {

struct GeoRasterPreview {
  cv::Mat samples;      // CV_32FC(bands), values as stored (no scaling); nodata as stored (NaN for float)
  GeoRasterGrid grid;   // of the preview: its size, and the GSD scaled to it
  std::string crs_name; // "WGS 84 / UTM zone 32N", empty without a CRS
  bool sixteen_bit = false;  // the stored samples are 16-bit
};

// Throws std::runtime_error naming `path` when GDAL cannot read it.
GeoRasterPreview ReadGeoRasterPreview(const std::filesystem::path& path, int max_side);

}  // namespace lutex
