// lutex's 3D Tiles in a real viewer: CesiumJS (pinned by scripts/cesium_viewer/package-lock.json) renders the
// tileset in headless Chromium, from a page served on 127.0.0.1, and the screenshot is checked.
//
// The scene is a flat 4 x 3 m seafloor whose true albedo is red in the north-west quadrant, green
// north-east, blue south-west and light grey south-east (face colours). `lutex simulate` renders six images
// of it, `lutex tiles` bakes a tileset of several levels from their true-albedo images in an ENU frame on
// the globe, and scripts/cesium_viewer/render.html looks straight down at it with heading 0. The
// screenshot must show a 4:3 rectangle with those colours in those corners: the root transform put the
// tiles on the globe, level and north up, the glTF content's +Y up was turned to 3D Tiles' +Z up once (not
// twice, not never), and the texture kept the seafloor's colours. The same tileset with its geometry
// compressed (EXT_meshopt_compression) must look the same.
//
// Skips when chromium, python3 (the HTTP server) or scripts/cesium_viewer/node_modules is absent
// (scripts/install_dependencies.sh installs them all).

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/stages/simulate_workspace.h"
#include "colmap_integration/stages/tiles_workspace.h"
#include "lib/geometry/mesh_io.h"
#include "tests/support/headless_browser.h"
#include "tests/support/run_command.h"
#include "tests/support/small_survey.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

constexpr int kWindowWidth = 800, kWindowHeight = 600;
// North-west, north-east, south-west, south-east (8-bit sRGB, as the faces store them).
const std::array<cv::Vec3b, 4> kQuadrants = {cv::Vec3b(230, 40, 40), cv::Vec3b(40, 200, 40), cv::Vec3b(40, 40, 230),
                                             cv::Vec3b(220, 220, 220)};

fs::path ViewerDir() { return fs::path(LUTEX_SOURCE_DIR) / "scripts" / "cesium_viewer"; }

// The 4 x 3 m plane centred on the origin (z up, +y north), 0.1 m cells, each face in its quadrant's colour.
Mesh QuadrantSeafloor() {
  Mesh mesh;
  const int columns = 40, rows = 30;
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= columns; ++i) mesh.vertices.emplace_back(-2.0 + 0.1 * i, -1.5 + 0.1 * j, 0.0);
  }
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const std::uint32_t a = j * (columns + 1) + i, b = a + 1, c = a + columns + 2, d = a + columns + 1;
      const int quadrant = (i >= columns / 2 ? 1 : 0) + (j < rows / 2 ? 2 : 0);  // south is j < rows / 2
      const cv::Vec3b& colour = kQuadrants[quadrant];
      for (const Mesh::Face& face : {Mesh::Face{a, b, c}, Mesh::Face{a, c, d}}) {
        mesh.faces.push_back(face);
        mesh.face_colors.emplace_back(colour[0], colour[1], colour[2]);
      }
    }
  }
  return mesh;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Empty when the viewer can run here, else why not (a reason to skip).
std::string MissingViewer() {
  if (!testing::HaveProgram("chromium")) return "chromium is not installed (scripts/install_dependencies.sh)";
  if (!testing::HaveProgram("python3")) return "python3 is not installed (it serves the page)";
  if (!fs::exists(ViewerDir() / "node_modules" / "cesium" / "Build" / "Cesium" / "Cesium.js")) {
    return "CesiumJS is not installed in " + ViewerDir().string() + " (scripts/install_dependencies.sh)";
  }
  return "";
}

// Bakes the quadrant seafloor's tileset with `gltf`, renders it and checks the screenshot.
void ExpectTheTilesetFromAbove(const GltfOptions& gltf) {
  testing::TempDir dir;
  WriteMesh(QuadrantSeafloor(), dir.path() / "seafloor.ply");
  nlohmann::json scene = testing::SmallSurveyScene();
  scene["mesh"] = "seafloor.ply";
  scene["albedo"] = "face_colors";
  std::ofstream(dir.path() / "scene.json") << scene.dump(1);
  SimulateOptions simulate;
  simulate.scene = dir.path() / "scene.json";
  simulate.output = dir.path() / "W";
  SimulateWorkspace(simulate);

  // The served folder: the viewer's page and CesiumJS (linked, not copied) beside the tileset.
  const fs::path site = dir.path() / "site";
  TilesOptions tiles;
  tiles.workspace = dir.path() / "W";
  tiles.mesh = tiles.workspace / "scene" / "mesh.ply";
  tiles.views.images = tiles.workspace / "ground_truth" / "albedo";
  tiles.views.image_encoding = ImageEncoding::kLinear16;
  tiles.output = site / "tiles";
  tiles.tree.max_faces = 300;
  tiles.gltf = gltf;
  tiles.georeference.enu_origin = "-17.5,146.5,-12";  // the Great Barrier Reef: south of the equator, east
  const TilesSummary summary = TilesWorkspace(tiles);
  ASSERT_GE(summary.depth, 2);
  fs::create_symlink(ViewerDir() / "render.html", site / "render.html");
  fs::create_directory_symlink(ViewerDir() / "node_modules", site / "node_modules");

  const fs::path server_log = dir.path() / "server.log";
  testing::LocalHttpServer server(site, server_log);
  ASSERT_NE(server.port(), 0) << "the HTTP server did not start: " << ReadText(server_log);
  const fs::path screenshot = dir.path() / "render.png";
  const std::string url =
      "http://127.0.0.1:" + std::to_string(server.port()) + "/render.html?tileset=/tiles/tileset.json";
  const std::string browser = testing::TakeScreenshot(url, screenshot, kWindowWidth, kWindowHeight);
  const std::string diagnostics = "chromium:\n" + browser + "\nserver:\n" + ReadText(server_log);
  ASSERT_TRUE(fs::exists(screenshot)) << diagnostics;
  ASSERT_NE(browser.find("lutex-cesium: rendered"), std::string::npos) << "render.html did not render\n" << diagnostics;
  // Cesium asked for the leaves (maximumScreenSpaceError 1 at this range).
  EXPECT_NE(ReadText(server_log).find("GET /tiles/0_0_"), std::string::npos) << "no leaf was loaded\n" << diagnostics;

  const cv::Mat picture = cv::imread(screenshot.string(), cv::IMREAD_COLOR);
  ASSERT_EQ(picture.cols, kWindowWidth);
  ASSERT_EQ(picture.rows, kWindowHeight);
  const cv::Rect bounds = testing::ExpectQuadrantsFromAbove(picture, 4.0 / 3.0, kQuadrants, "CesiumJS");
  EXPECT_NEAR(bounds.x + 0.5 * bounds.width, 0.5 * kWindowWidth, 15.0) << "not centred";
  EXPECT_NEAR(bounds.y + 0.5 * bounds.height, 0.5 * kWindowHeight, 15.0) << "not centred";
  const bool failed = ::testing::Test::HasFailure();
  if (failed || std::getenv("LUTEX_KEEP_SCREENSHOTS")) {
    const fs::path kept = fs::temp_directory_path() /
                          (gltf.meshopt_compression ? "lutex_cesium_render_meshopt.png" : "lutex_cesium_render.png");
    fs::copy_file(screenshot, kept, fs::copy_options::overwrite_existing);
    std::cout << "the screenshot is kept as " << kept.string() << "\n" << (failed ? diagnostics : "") << "\n";
  }
}

TEST(CesiumRender, TheTilesetIsOnTheGlobeSeenFromAboveNorthUpInTheSeafloorsColours) {
  if (const std::string missing = MissingViewer(); !missing.empty()) GTEST_SKIP() << missing;
  ExpectTheTilesetFromAbove(GltfOptions{});
}

TEST(CesiumRender, AMeshoptCompressedTilesetLooksTheSame) {
  if (const std::string missing = MissingViewer(); !missing.empty()) GTEST_SKIP() << missing;
  GltfOptions gltf;
  gltf.meshopt_compression = true;
  ExpectTheTilesetFromAbove(gltf);
}

}  // namespace
}  // namespace lutex
