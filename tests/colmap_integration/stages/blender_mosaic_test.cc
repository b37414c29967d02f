// lutex mosaic on the Blender seafloor (../shared/datasets/dev/seafloor_clear), mapped from the
// ground-truth albedo images with the true poses and mesh:
//   - against the true orthophoto (the mesh with its albedo texture seen from above, the shared
//     ortho_error.py): colour and DEM error;
//   - the same scene moved to UTM-sized coordinates in the model itself gives the same pixels (doubles end
//     to end);
//   - an ENU model lands at the UTM coordinates an independent conversion gives (to within a pixel).
// Skips without the datasets.

#include <cmath>
#include <cstring>
#include <regex>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/mosaic_workspace.h"
#include "lib/geometry/mesh_io.h"
#include "tests/support/enu_to_utm.h"
#include "tests/support/geotiff.h"
#include "tests/support/run_command.h"
#include "tests/support/shared_datasets.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

class BlenderMosaic : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dev = testing::SharedDevDatasets();
    if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
    tools_ = dev->parent_path().parent_path() / "tools";
    survey_ = *dev / "seafloor_clear";
  }

  // From gt/albedo (EXR), 16-bit linear, into `folder`.
  MosaicOptions Mapping(const fs::path& workspace, const fs::path& mesh, const fs::path& folder, double gsd) const {
    MosaicOptions options;
    options.workspace = workspace;
    options.mesh = mesh;
    options.views.images = survey_ / "gt" / "albedo";
    options.views.image_encoding = ImageEncoding::kFloat;
    options.gsd = gsd;
    options.encoding = ImageEncoding::kLinear16;
    options.output = folder / "ortho.tif";
    options.dem = folder / "dem.tif";
    return options;
  }

  fs::path tools_, survey_;
};

TEST_F(BlenderMosaic, GroundTruthAlbedoMapsWithinOnePercentAndItsHeightsWithinAMillimetre) {
  testing::TempDir dir;
  MosaicOptions options = Mapping(survey_, survey_ / "scene" / "mesh.ply", dir.path(), 0.005);
  options.georeference.crs = "EPSG:32632";
  options.georeference.crs_origin = "500000,6000000,-800";
  const MosaicSummary summary = MosaicWorkspace(options);
  const testing::CommandResult metric = testing::RunCommand(
      "/usr/bin/python3 '" + (tools_ / "ortho_error.py").string() + "' '" + survey_.string() + "' '" +
      (dir.path() / "ortho.tif").string() + "' --crs-origin 500000,6000000,-800 --dem '" +
      (dir.path() / "dem.tif").string() + "'");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(metric.output, match,
                                std::regex("mae=([0-9.]+) median=[0-9.]+ p95=([0-9.]+) valid=([0-9.]+) "
                                           "dem_median_mm=([0-9.]+)")))
      << metric.output;
  std::printf("mosaic from gt/albedo at 5 mm: %d x %d, %zu tiles; ortho_error.py: %s", summary.grid.raster.width,
              summary.grid.raster.height, summary.mosaic.num_tiles, metric.output.c_str());
  EXPECT_LE(std::stod(match[1]), 1.0);   // mae, pp: the goal
  EXPECT_LE(std::stod(match[4]), 1.0);   // DEM median error, mm
  EXPECT_GE(std::stod(match[3]), 0.8);   // the images see 86 % of the mesh from above
}

TEST_F(BlenderMosaic, AModelAtUtmCoordinatesGivesTheSamePixels) {
  testing::TempDir dir;
  const Eigen::Vector3d origin(500000.0, 6000000.0, -800.0);
  // The survey moved into UTM 32N in the model itself: world + origin, poses and mesh.
  const fs::path moved = dir.path() / "W";
  SparseModel model = ReadSparseModel(survey_ / "sparse" / "0");
  for (auto& [id, image] : model.images) {
    image.cam_from_world.translation -= image.cam_from_world.rotation * origin;
  }
  WriteSparseModel(model, moved / "sparse" / "0", SparseFormat::kBinary);
  fs::create_directory_symlink(survey_ / "images", moved / "images");
  Mesh mesh = ReadMesh(survey_ / "scene" / "mesh.ply");
  for (Eigen::Vector3d& vertex : mesh.vertices) vertex += origin;
  WriteMesh(mesh, moved / "mesh.ply");

  MosaicOptions shifted = Mapping(survey_, survey_ / "scene" / "mesh.ply", dir.path() / "shifted", 0.01);
  shifted.georeference.crs = "EPSG:32632";
  shifted.georeference.crs_origin = "500000,6000000,-800";
  MosaicWorkspace(shifted);
  MosaicOptions in_utm = Mapping(moved, moved / "mesh.ply", dir.path() / "in_utm", 0.01);
  in_utm.georeference.crs = "EPSG:32632";
  MosaicWorkspace(in_utm);

  for (const char* file : {"ortho.tif", "dem.tif"}) {
    const testing::GeoTiff a = testing::ReadGeoTiff(dir.path() / "shifted" / file);
    const testing::GeoTiff b = testing::ReadGeoTiff(dir.path() / "in_utm" / file);
    ASSERT_EQ(a.samples.size(), b.samples.size()) << file;
    EXPECT_EQ(a.geotransform, b.geotransform) << file;
    EXPECT_EQ(a.epsg, "32632");
    EXPECT_EQ(b.epsg, "32632");
    cv::Mat difference;
    cv::absdiff(a.samples, b.samples, difference);
    cv::patchNaNs(difference, 0.0);
    double most = 0.0;
    cv::minMaxLoc(difference.reshape(1), nullptr, &most);
    // Colours to one 16-bit step, heights to 1 mm.
    EXPECT_LE(most, std::string(file) == "dem.tif" ? 1e-3 : 1.0) << file;
  }
}

// One thread without the decoded-image cache, two with it (the default): the same bytes.
TEST_F(BlenderMosaic, OneAndTwoThreadsWithAndWithoutTheImageCacheMakeTheSamePixels) {
  testing::TempDir dir;
  std::vector<testing::GeoTiff> maps;
  for (int threads : {1, 2}) {
    MosaicOptions options = Mapping(survey_, survey_ / "scene" / "mesh.ply", dir.path() / std::to_string(threads), 0.01);
    options.ortho.tile_size = 256;  // several tiles
    options.ortho.baking.num_threads = threads;
    if (threads == 1) options.picture_cache_bytes = 0;
    MosaicWorkspace(options);
    maps.push_back(testing::ReadGeoTiff(dir.path() / std::to_string(threads) / "ortho.tif"));
    maps.push_back(testing::ReadGeoTiff(dir.path() / std::to_string(threads) / "dem.tif"));
  }
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(maps[k].samples.size(), maps[k + 2].samples.size());
    const cv::Mat& a = maps[k].samples;
    const cv::Mat& b = maps[k + 2].samples;
    EXPECT_EQ(std::memcmp(a.data, b.data, a.total() * a.elemSize()), 0) << (k ? "dem" : "ortho");
  }
}

TEST_F(BlenderMosaic, AnEnuModelLandsAtTheUtmCoordinatesOfAnIndependentConversion) {
  testing::TempDir dir;
  const double lat = 54.3201, lon = 10.1402, h = -30.0;  // 1.1 degrees east of UTM 32's meridian
  MosaicOptions local = Mapping(survey_, survey_ / "scene" / "mesh.ply", dir.path() / "local", 0.01);
  local.georeference.crs = "EPSG:32632";  // the model's own x, y as map coordinates
  MosaicWorkspace(local);
  MosaicOptions enu = Mapping(survey_, survey_ / "scene" / "mesh.ply", dir.path() / "enu", 0.01);
  enu.georeference.enu_origin = "54.3201,10.1402,-30";
  const MosaicSummary summary = MosaicWorkspace(enu);
  EXPECT_EQ(summary.crs, "EPSG:32632");

  const testing::GeoTiff a = testing::ReadGeoTiff(dir.path() / "local" / "ortho.tif");
  const testing::GeoTiff b = testing::ReadGeoTiff(dir.path() / "enu" / "ortho.tif");
  ASSERT_FALSE(a.samples.empty());
  ASSERT_FALSE(b.samples.empty());
  EXPECT_EQ(b.epsg, "32632");
  cv::Mat a_rgb, b_rgb;
  cv::cvtColor(a.samples, a_rgb, cv::COLOR_RGBA2RGB);
  cv::cvtColor(b.samples, b_rgb, cv::COLOR_RGBA2RGB);
  // Patches of the local map around points of the scene, found in the ENU map near where the oracle puts
  // them: the grid convergence here (~0.9 degrees) alone would move the corners by 5-10 pixels.
  const int half = 15, search = 12;
  int checked = 0;
  for (double x : {-3.5, 0.0, 3.5}) {
    for (double y : {-2.0, 0.0, 2.0}) {
      const int col = static_cast<int>(std::lround((x - a.geotransform[0]) / a.geotransform[1] - 0.5));
      const int row = static_cast<int>(std::lround((y - a.geotransform[3]) / a.geotransform[5] - 0.5));
      const cv::Rect patch(col - half, row - half, 2 * half + 1, 2 * half + 1);
      if ((patch & cv::Rect(0, 0, a_rgb.cols, a_rgb.rows)) != patch) continue;
      if (cv::countNonZero(a.samples(patch).reshape(1).col(3) == 0) > 0) continue;  // not all seen
      cv::Scalar mean, deviation;
      cv::meanStdDev(a_rgb(patch), mean, deviation);
      if (deviation[0] + deviation[1] + deviation[2] < 3 * 0.02 * 65535) continue;  // too plain to find
      // The patch centre's exact point, then where the oracle puts it.
      const Eigen::Vector3d point(a.geotransform[0] + (col + 0.5) * a.geotransform[1],
                                  a.geotransform[3] + (row + 0.5) * a.geotransform[5], 0.0);
      const Eigen::Vector3d utm = testing::ProjectedOfEnu(point, lat, lon, h, "EPSG:32632");
      const double expected_col = (utm.x() - b.geotransform[0]) / b.geotransform[1] - 0.5;
      const double expected_row = (utm.y() - b.geotransform[3]) / b.geotransform[5] - 0.5;
      const cv::Rect window(static_cast<int>(std::lround(expected_col)) - half - search,
                            static_cast<int>(std::lround(expected_row)) - half - search, 2 * (half + search) + 1,
                            2 * (half + search) + 1);
      if ((window & cv::Rect(0, 0, b_rgb.cols, b_rgb.rows)) != window) continue;
      cv::Mat scores;
      cv::matchTemplate(b_rgb(window), a_rgb(patch), scores, cv::TM_SQDIFF);
      cv::Point best;
      cv::minMaxLoc(scores, nullptr, nullptr, &best, nullptr);
      const double found_col = window.x + best.x + half, found_row = window.y + best.y + half;
      EXPECT_LE(std::abs(found_col - expected_col), 1.0) << x << ", " << y;
      EXPECT_LE(std::abs(found_row - expected_row), 1.0) << x << ", " << y;
      ++checked;
    }
  }
  EXPECT_GE(checked, 6);
}

}  // namespace
}  // namespace lutex
