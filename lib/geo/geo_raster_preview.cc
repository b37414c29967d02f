#include "lib/geo/geo_raster_preview.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

namespace lutex {

GeoRasterPreview ReadGeoRasterPreview(const std::filesystem::path& path, int max_side) {
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetH dataset = GDALOpen(path.c_str(), GA_ReadOnly);
  CPLPopErrorHandler();
  if (!dataset) throw std::runtime_error(path.string() + ": GDAL cannot read it (" + CPLGetLastErrorMsg() + ")");
  const int width = GDALGetRasterXSize(dataset), height = GDALGetRasterYSize(dataset);
  const int bands = GDALGetRasterCount(dataset);
  const double scale = std::min(1.0, double(std::max(1, max_side)) / double(std::max(width, height)));
  GeoRasterPreview preview;
  preview.grid.width = std::max(1, static_cast<int>(std::lround(width * scale)));
  preview.grid.height = std::max(1, static_cast<int>(std::lround(height * scale)));
  double geotransform[6] = {0, 1, 0, 0, 0, -1};
  GDALGetGeoTransform(dataset, geotransform);
  preview.grid.west = geotransform[0];
  preview.grid.north = geotransform[3];
  preview.grid.gsd = geotransform[1] * double(width) / double(preview.grid.width);
  preview.sixteen_bit = bands > 0 && GDALGetRasterDataType(GDALGetRasterBand(dataset, 1)) == GDT_UInt16;
  const char* wkt = GDALGetProjectionRef(dataset);
  if (wkt && *wkt) {
    preview.grid.crs_wkt = wkt;
    OGRSpatialReferenceH srs = OSRNewSpatialReference(wkt);
    if (srs) {
      const char* name = OSRGetName(srs);
      if (name) preview.crs_name = name;
      OSRDestroySpatialReference(srs);
    }
  }
  preview.samples = cv::Mat(preview.grid.height, preview.grid.width, CV_32FC(std::max(1, bands)));
  const auto pixel = static_cast<GSpacing>(sizeof(float) * bands);
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.eResampleAlg = GRIORA_Average;
  const CPLErr read = GDALDatasetRasterIOEx(dataset, GF_Read, 0, 0, width, height, preview.samples.data,
                                            preview.grid.width, preview.grid.height, GDT_Float32, bands, nullptr,
                                            pixel, pixel * preview.grid.width, sizeof(float), &extra);
  GDALClose(dataset);
  if (read != CE_None) throw std::runtime_error(path.string() + ": GDAL cannot read its pixels");
  return preview;
}

}  // namespace lutex
