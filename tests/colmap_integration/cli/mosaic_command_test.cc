// lutex mosaic from the command line: bad input is one clear line and writes nothing; on the Blender
// seafloor, the GeoTIFFs are what gdalinfo and QGIS expect (CRS, pixel size, COG layout).

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geometry/mesh_primitives.h"
#include "tests/support/run_command.h"
#include "tests/support/shared_datasets.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// Three 64x48 images looking down at the plane z = 0 (their bytes are never decoded: every fault below is
// found before), a plane mesh and a vertical wall.
void MakeWorkspace(const fs::path& root) {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 64, 48, 40.0, 40.0);
  fs::create_directories(root / "images");
  for (std::uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "img" + std::to_string(id) + ".png";
    image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.3 * id, 0, 2.0), Eigen::Vector3d(0, 0, -1),
                                                 Eigen::Vector3d(0, -1, 0));
    model.images[id] = image;
    std::ofstream(root / "images" / image.name) << "image bytes";
  }
  WriteSparseModel(model, root / "sparse" / "0", SparseFormat::kBinary);
  WriteMesh(MakeHeightFieldMesh([](double, double) { return 0.0; }, -2, 2, -2, 2, 4, 4), root / "plane.ply");
  Mesh wall;
  wall.vertices = {{0, -2, -1}, {0, 2, -1}, {0, 2, 1}, {0, -2, 1}};
  wall.faces = {{0, 1, 2}, {0, 2, 3}};
  WriteMesh(wall, root / "wall.ply");
}

TEST(MosaicCommand, BadInputIsOneClearLineAndWritesNothing) {
  struct Case {
    std::string options;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"--crs EPSG:999999", "EPSG:999999: the CRS is unknown to PROJ"},
      {"--crs EPSG:4326", "EPSG:4326: not a projected CRS"},
      {"--enu-origin 95,10,0", "latitude must be in [-90, 90]"},
      {"--enu-origin 54,10", "must be three numbers"},
      {"--crs-origin 1,2,3", "--crs-origin needs --crs"},
      {"--gsd -0.01", "--gsd must be a positive number"},
      {"--gsd 1e-7", "would make a mosaic of 40000000 x 40000000 pixels (1.6e+15)"},
      {"--encoding float", "--encoding must be srgb8 or linear16"},
      {"--output W/ortho.png", "--output must be a .tif"},
      {"--mesh-override", "the mesh has no surface seen from above"},
  };
  for (const Case& c : cases) {
    testing::TempDir dir;
    const fs::path w = dir.path() / "W";
    MakeWorkspace(w);
    std::string options = c.options;
    std::string mesh = (w / "plane.ply").string();
    if (options == "--mesh-override") {
      options = "--gsd 0.05";
      mesh = (w / "wall.ply").string();
    }
    const std::size_t at = options.find("W/");
    if (at != std::string::npos) options.replace(at, 1, w.string());
    const testing::CommandResult result = testing::RunCommand(std::string(LUTEX_BINARY) + " mosaic --workspace " +
                                                              w.string() + " --mesh " + mesh + " " + options);
    EXPECT_EQ(result.exit_code, 1) << c.options << "\n" << result.output;
    int error_lines = 0;
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) error_lines += line.find("error") != std::string::npos;
    EXPECT_EQ(error_lines, 1) << c.options << "\n" << result.output;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << c.options << "\n" << result.output;
    EXPECT_FALSE(fs::exists(w / "lutex")) << c.options << ": something was written";
  }
}

TEST(MosaicCommand, TheGeoTiffsAreCloudOptimizedInTheUtmZoneOfAnEnuModel) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  const fs::path survey = *dev / "seafloor_clear";
  testing::TempDir dir;
  const testing::CommandResult run = testing::RunCommand(
      std::string(LUTEX_BINARY) + " mosaic --workspace " + survey.string() + " --mesh " +
      (survey / "scene" / "mesh.ply").string() + " --images " + (survey / "gt" / "albedo").string() +
      " --image-encoding float --gsd 0.01 --enu-origin 54.3201,10.1402,-30 --output " +
      (dir.path() / "ortho.tif").string() + " --dem " + (dir.path() / "dem.tif").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("map frame: EPSG:32632 (WGS 84 / UTM zone 32N)"), std::string::npos) << run.output;
  for (const char* file : {"ortho.tif", "dem.tif"}) {
    const testing::CommandResult info = testing::RunCommand("gdalinfo " + (dir.path() / file).string());
    ASSERT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("LAYOUT=COG"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("WGS 84 / UTM zone 32N"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("Pixel Size = (0.010000000000000,-0.010000000000000)"), std::string::npos)
        << info.output;
    EXPECT_NE(info.output.find("Block=512x512"), std::string::npos) << info.output;
  }
  // gdal_translate reads it back whole.
  EXPECT_EQ(testing::RunCommand("gdal_translate -q -of PNG " + (dir.path() / "ortho.tif").string() + " " +
                                (dir.path() / "ortho.png").string())
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(dir.path() / "ortho.png"));
}

}  // namespace
}  // namespace lutex
