#pragma once

// Pictures of the map products for the report: the orthomosaic and the DEM read small from their
// GeoTIFFs (lib/geo/geo_raster_preview.h), north up, each with a scale bar in metres.
//   orthomosaic   its colours (16-bit linear shown as sRGB), nodata on mid grey
//   DEM           heights colour-mapped (viridis: low dark blue, high yellow), nodata on mid grey

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace lutex {

struct MapPreview {
  cv::Mat bgr8;            // the picture
  double metres_per_pixel = 0.0;
  double scale_bar_metres = 0.0;  // the bar drawn at the bottom left
  double low = 0.0, high = 0.0;   // DEM: the heights at the two ends of the colour map
  std::string crs_name;           // empty without a CRS
};

// Throw std::runtime_error naming the file when GDAL cannot read it.
MapPreview OrthomosaicPreview(const std::filesystem::path& ortho, int max_side);
MapPreview DemPreview(const std::filesystem::path& dem, int max_side);

// The longest 1-2-5 length (0.01 m ... 10 km) no longer than a quarter of `width_metres`.
double ScaleBarLength(double width_metres);

}  // namespace lutex
