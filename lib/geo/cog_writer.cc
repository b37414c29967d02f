#include "lib/geo/cog_writer.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>

namespace lutex {

namespace fs = std::filesystem;

namespace {

// GDAL's string lists, freed with their owner.
struct Options {
  char** list = nullptr;
  ~Options() { CSLDestroy(list); }
  Options& Set(const char* key, const std::string& value) {
    list = CSLSetNameValue(list, key, value.c_str());
    return *this;
  }
};

int BandsOf(GeoRasterKind kind) { return kind == GeoRasterKind::kFloat32 ? 1 : 4; }

GDALDataType TypeOf(GeoRasterKind kind) {
  switch (kind) {
    case GeoRasterKind::kRgba8: return GDT_Byte;
    case GeoRasterKind::kRgba16: return GDT_UInt16;
    case GeoRasterKind::kFloat32: return GDT_Float32;
  }
  return GDT_Byte;
}

int CvTypeOf(GeoRasterKind kind) {
  switch (kind) {
    case GeoRasterKind::kRgba8: return CV_8UC4;
    case GeoRasterKind::kRgba16: return CV_16UC4;
    case GeoRasterKind::kFloat32: return CV_32FC1;
  }
  return CV_8UC4;
}

std::string LastGdalError() {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? message : "GDAL gave no reason";
}

}  // namespace

CogWriter::CogWriter(const fs::path& destination, const GeoRasterGrid& grid, GeoRasterKind kind,
                     std::size_t cache_bytes)
    : grid_(grid), kind_(kind), output_(destination), staging_(output_.temporary_path().string() + ".staging.tif") {
  if (grid.width <= 0 || grid.height <= 0 || !(grid.gsd > 0.0)) {
    throw std::invalid_argument(destination.string() + ": empty raster grid");
  }
  GDALAllRegister();
  GDALSetCacheMax64(static_cast<GIntBig>(cache_bytes));
  GDALDriverH gtiff = GDALGetDriverByName("GTiff");
  if (!gtiff) throw std::runtime_error("GDAL has no GTiff driver");
  Options options;
  options.Set("TILED", "YES").Set("BLOCKXSIZE", "512").Set("BLOCKYSIZE", "512").Set("COMPRESS", "ZSTD");
  options.Set("ZSTD_LEVEL", "1").Set("BIGTIFF", "IF_SAFER");
  if (kind != GeoRasterKind::kFloat32) options.Set("PHOTOMETRIC", "RGB").Set("ALPHA", "YES");
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  dataset_ = GDALCreate(gtiff, staging_.c_str(), grid.width, grid.height, BandsOf(kind),
                        TypeOf(kind), options.list);
  CPLPopErrorHandler();
  if (!dataset_) Fail("cannot create the staging file " + staging_.string());
  double geotransform[6] = {grid.west, grid.gsd, 0.0, grid.north, 0.0, -grid.gsd};
  GDALSetGeoTransform(dataset_, geotransform);
  if (!grid.crs_wkt.empty() && GDALSetProjection(dataset_, grid.crs_wkt.c_str()) != CE_None) {
    const std::string reason = LastGdalError();
    GDALClose(dataset_);
    dataset_ = nullptr;
    std::error_code ignored;
    fs::remove(staging_, ignored);
    Fail("GDAL does not take the CRS: " + reason);
  }
  if (kind == GeoRasterKind::kFloat32) {
    GDALSetRasterNoDataValue(GDALGetRasterBand(dataset_, 1), std::numeric_limits<double>::quiet_NaN());
  }
}

CogWriter::~CogWriter() {
  if (dataset_) GDALClose(dataset_);
  std::error_code ignored;
  fs::remove(staging_, ignored);
}

void CogWriter::Fail(const std::string& what) const {
  std::error_code error;
  const fs::space_info space = fs::space(output_.destination().parent_path().empty() ? fs::path(".")
                                                                                    : output_.destination().parent_path(),
                                         error);
  if (!error && space.available < (std::uintmax_t{16} << 20)) {
    throw std::runtime_error(output_.destination().string() + ": the disk is full (" + what + ")");
  }
  throw std::runtime_error(output_.destination().string() + ": " + what);
}

void CogWriter::WriteTile(int col, int row, const cv::Mat& tile) {
  if (tile.type() != CvTypeOf(kind_) || !tile.isContinuous()) {
    throw std::invalid_argument("CogWriter: a tile of the wrong type");
  }
  if (col < 0 || row < 0 || col + tile.cols > grid_.width || row + tile.rows > grid_.height) {
    throw std::invalid_argument("CogWriter: a tile outside the grid");
  }
  const int bands = BandsOf(kind_);
  const auto pixel = static_cast<GSpacing>(tile.elemSize());
  const auto line = static_cast<GSpacing>(tile.step[0]);
  const auto band = static_cast<GSpacing>(tile.elemSize1());
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const CPLErr result = GDALDatasetRasterIOEx(dataset_, GF_Write, col, row, tile.cols, tile.rows,
                                              const_cast<uchar*>(tile.data), tile.cols, tile.rows, TypeOf(kind_), bands,
                                              nullptr, pixel, line, band, nullptr);
  CPLPopErrorHandler();
  if (result != CE_None) Fail("writing failed: " + LastGdalError());
}

void CogWriter::Convert(int num_threads) {
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALFlushCache(dataset_);
  CPLPopErrorHandler();
  if (CPLGetLastErrorType() >= CE_Failure) Fail("writing failed: " + LastGdalError());
  GDALDriverH cog = GDALGetDriverByName("COG");
  if (!cog) throw std::runtime_error("GDAL has no COG driver (GDAL 3.1 or newer is needed)");
  Options options;
  options.Set("BLOCKSIZE", "512").Set("COMPRESS", "DEFLATE").Set("BIGTIFF", "IF_SAFER");
  options.Set("PREDICTOR", "YES").Set("RESAMPLING", "AVERAGE").Set("OVERVIEWS", "IF_NEEDED");
  options.Set("NUM_THREADS", std::to_string(std::max(1, num_threads)));
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetH copy = GDALCreateCopy(cog, output_.temporary_path().c_str(), dataset_, FALSE, options.list, nullptr,
                                     nullptr);
  if (copy) GDALClose(copy);
  const bool closed = copy && CPLGetLastErrorType() < CE_Failure;
  CPLPopErrorHandler();
  if (!closed) {
    std::error_code ignored;
    fs::remove(output_.temporary_path(), ignored);
    Fail("writing the COG failed: " + LastGdalError());
  }
  GDALClose(dataset_);
  dataset_ = nullptr;
  std::error_code ignored;
  fs::remove(staging_, ignored);
}

void CogWriter::Commit() { output_.Commit(); }

}  // namespace lutex
