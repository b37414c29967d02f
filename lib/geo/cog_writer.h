#pragma once

// A Cloud-Optimized GeoTIFF (COG) written tile by tile, through GDAL, in bounded memory: the tiles go
// into a tiled staging GeoTIFF beside the output (ZSTD, named after the output's temporary, so the next
// run removes it if this one is killed), which GDAL's COG driver then copies into the output with
// overviews (tiled 512, DEFLATE, which every GIS reads). The output is written under a temporary name and
// renamed by Commit(); the staging file is removed either way.
// GDAL's block cache, shared by the process, is set to `cache_bytes`.
//
// Raster kinds:
//   kRgba8     sRGB colour + alpha (0: nodata), CV_8UC4 tiles (R, G, B, A order)
//   kRgba16    linear colour + alpha (0: nodata), CV_16UC4 tiles
//   kFloat32   one band, NaN nodata (elevations), CV_32FC1 tiles

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "lib/util/atomic_output.h"

namespace lutex {

// A north-up grid: pixel (col, row) covers [west + col gsd, west + (col + 1) gsd] x
// [north - (row + 1) gsd, north - row gsd] in the CRS.
struct GeoRasterGrid {
  int width = 0;
  int height = 0;
  double west = 0.0;
  double north = 0.0;
  double gsd = 0.0;
  std::string crs_wkt;  // empty: no CRS (a local frame)
};

enum class GeoRasterKind { kRgba8, kRgba16, kFloat32 };

class CogWriter {
 public:
  // Throws std::runtime_error naming `destination` when the staging file cannot be created.
  CogWriter(const std::filesystem::path& destination, const GeoRasterGrid& grid, GeoRasterKind kind,
            std::size_t cache_bytes);
  ~CogWriter();
  CogWriter(const CogWriter&) = delete;
  CogWriter& operator=(const CogWriter&) = delete;

  // `tile` (of the kind's type) at pixel (col, row) of the grid; it must lie inside the grid.
  void WriteTile(int col, int row, const cv::Mat& tile);
  // Converts to the COG under its temporary name (with `num_threads` compressing). Throws naming the
  // destination, and saying so when the disk is full.
  void Convert(int num_threads);
  // Renames the converted COG into place (after Convert: several files converted, then all committed).
  void Commit();

  const std::filesystem::path& destination() const { return output_.destination(); }

 private:
  [[noreturn]] void Fail(const std::string& what) const;

  GeoRasterGrid grid_;
  GeoRasterKind kind_;
  AtomicOutputFile output_;
  std::filesystem::path staging_;  // removed with the writer
  void* dataset_ = nullptr;        // GDALDatasetH of the staging file
};

}  // namespace lutex
