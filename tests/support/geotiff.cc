#include "tests/support/geotiff.h"

#include <vector>

#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

namespace lutex::testing {

GeoTiff ReadGeoTiff(const std::filesystem::path& path) {
  GeoTiff tiff;
  GDALAllRegister();
  GDALDatasetH dataset = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!dataset) {
    ADD_FAILURE() << path << ": GDAL cannot open it";
    return tiff;
  }
  const int width = GDALGetRasterXSize(dataset), height = GDALGetRasterYSize(dataset);
  const int bands = GDALGetRasterCount(dataset);
  GDALGetGeoTransform(dataset, tiff.geotransform.data());
  const char* wkt = GDALGetProjectionRef(dataset);
  if (wkt && *wkt) {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(wkt);
    if (OSRAutoIdentifyEPSG(srs) == OGRERR_NONE && OSRGetAuthorityCode(srs, nullptr)) {
      tiff.epsg = OSRGetAuthorityCode(srs, nullptr);
    }
    OSRDestroySpatialReference(srs);
  }
  tiff.samples = cv::Mat(height, width, CV_32FC(bands));
  const auto pixel = static_cast<GSpacing>(sizeof(float) * bands);
  if (GDALDatasetRasterIOEx(dataset, GF_Read, 0, 0, width, height, tiff.samples.data, width, height, GDT_Float32, bands,
                            nullptr, pixel, pixel * width, sizeof(float), nullptr) != CE_None) {
    ADD_FAILURE() << path << ": GDAL cannot read it";
    tiff.samples = cv::Mat();
  }
  GDALClose(dataset);
  return tiff;
}

}  // namespace lutex::testing
