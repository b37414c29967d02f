#include "lib/geo/cog_writer.h"

#include <cmath>
#include <limits>

#include <cpl_string.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include "lib/geo/map_frame.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

GeoRasterGrid UtmGrid() {
  Georeference georeference;
  georeference.frame = Georeference::Frame::kProjected;
  georeference.crs = "EPSG:32632";
  GeoRasterGrid grid;
  grid.width = 700;
  grid.height = 600;
  grid.west = 500000.0;
  grid.north = 6000000.0;
  grid.gsd = 0.005;
  grid.crs_wkt = MapFrame(georeference).crs_wkt();
  return grid;
}

std::size_t FilesIn(const fs::path& folder) {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++count;
  return count;
}

TEST(CogWriter, TilesComeBackAsACloudOptimizedGeoTiffWithItsGridAndCrs) {
  testing::TempDir dir;
  const GeoRasterGrid grid = UtmGrid();
  const fs::path ortho = dir.path() / "ortho.tif", dem = dir.path() / "dem.tif";
  {
    CogWriter colour(ortho, grid, GeoRasterKind::kRgba8, 64 << 20);
    CogWriter heights(dem, grid, GeoRasterKind::kFloat32, 64 << 20);
    for (int row = 0; row < grid.height; row += 512) {
      for (int col = 0; col < grid.width; col += 512) {
        const cv::Size size(std::min(512, grid.width - col), std::min(512, grid.height - row));
        cv::Mat rgba(size, CV_8UC4), z(size, CV_32FC1);
        for (int r = 0; r < size.height; ++r) {
          for (int c = 0; c < size.width; ++c) {
            const int x = col + c, y = row + r;
            rgba.at<cv::Vec4b>(r, c) = {uchar(x % 256), uchar(y % 256), uchar((x + y) % 256), uchar(x < 10 ? 0 : 255)};
            z.at<float>(r, c) = x < 10 ? std::numeric_limits<float>::quiet_NaN() : float(-800.0 + 0.001 * (x + y));
          }
        }
        colour.WriteTile(col, row, rgba);
        heights.WriteTile(col, row, z);
      }
    }
    colour.Convert(2);
    heights.Convert(2);
    colour.Commit();
    heights.Commit();
  }
  EXPECT_EQ(FilesIn(dir.path()), 2u);  // no staging file, no temporary

  GDALAllRegister();
  GDALDatasetH dataset = GDALOpen(ortho.c_str(), GA_ReadOnly);
  ASSERT_NE(dataset, nullptr);
  EXPECT_EQ(GDALGetRasterXSize(dataset), 700);
  EXPECT_EQ(GDALGetRasterYSize(dataset), 600);
  EXPECT_EQ(GDALGetRasterCount(dataset), 4);
  double geotransform[6];
  ASSERT_EQ(GDALGetGeoTransform(dataset, geotransform), CE_None);
  EXPECT_DOUBLE_EQ(geotransform[0], 500000.0);
  EXPECT_DOUBLE_EQ(geotransform[1], 0.005);
  EXPECT_DOUBLE_EQ(geotransform[3], 6000000.0);
  EXPECT_DOUBLE_EQ(geotransform[5], -0.005);
  OGRSpatialReferenceH srs = OSRNewSpatialReference(GDALGetProjectionRef(dataset));
  ASSERT_EQ(OSRAutoIdentifyEPSG(srs), OGRERR_NONE);
  EXPECT_STREQ(OSRGetAuthorityCode(srs, nullptr), "32632");
  OSRDestroySpatialReference(srs);
  const char* layout = GDALGetMetadataItem(dataset, "LAYOUT", "IMAGE_STRUCTURE");
  ASSERT_NE(layout, nullptr);
  EXPECT_STREQ(layout, "COG");
  EXPECT_EQ(GDALGetRasterColorInterpretation(GDALGetRasterBand(dataset, 4)), GCI_AlphaBand);
  EXPECT_GE(GDALGetOverviewCount(GDALGetRasterBand(dataset, 1)), 1);
  int block_x = 0, block_y = 0;
  GDALGetBlockSize(GDALGetRasterBand(dataset, 1), &block_x, &block_y);
  EXPECT_EQ(block_x, 512);
  std::vector<unsigned char> pixel(4);
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{5, 5}, {600, 550}, {511, 512}}) {
    ASSERT_EQ(GDALDatasetRasterIO(dataset, GF_Read, x, y, 1, 1, pixel.data(), 1, 1, GDT_Byte, 4, nullptr, 4, 4, 1),
              CE_None);
    EXPECT_EQ(pixel[0], x % 256);
    EXPECT_EQ(pixel[1], y % 256);
    EXPECT_EQ(pixel[2], (x + y) % 256);
    EXPECT_EQ(pixel[3], x < 10 ? 0 : 255);
  }
  GDALClose(dataset);

  dataset = GDALOpen(dem.c_str(), GA_ReadOnly);
  ASSERT_NE(dataset, nullptr);
  GDALRasterBandH band = GDALGetRasterBand(dataset, 1);
  EXPECT_EQ(GDALGetRasterDataType(band), GDT_Float32);
  int has_nodata = 0;
  EXPECT_TRUE(std::isnan(GDALGetRasterNoDataValue(band, &has_nodata)));
  EXPECT_TRUE(has_nodata);
  float z = 0.0f;
  ASSERT_EQ(GDALRasterIO(band, GF_Read, 600, 550, 1, 1, &z, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_FLOAT_EQ(z, float(-800.0 + 0.001 * 1150));
  ASSERT_EQ(GDALRasterIO(band, GF_Read, 3, 550, 1, 1, &z, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_TRUE(std::isnan(z));
  GDALClose(dataset);
}

TEST(CogWriter, AnUnfinishedWriterLeavesNothing) {
  testing::TempDir dir;
  {
    CogWriter writer(dir.path() / "ortho.tif", UtmGrid(), GeoRasterKind::kRgba16, 16 << 20);
    writer.WriteTile(0, 0, cv::Mat(16, 16, CV_16UC4, cv::Scalar::all(1000)));
    EXPECT_THROW(writer.WriteTile(690, 0, cv::Mat(16, 16, CV_16UC4)), std::invalid_argument);  // off the grid
    EXPECT_THROW(writer.WriteTile(0, 0, cv::Mat(16, 16, CV_8UC4)), std::invalid_argument);     // wrong type
  }  // e.g. an exception in the work before Finish
  EXPECT_EQ(FilesIn(dir.path()), 0u);
}

}  // namespace
}  // namespace lutex
