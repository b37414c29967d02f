// lutex's GLB in a real viewer: three.js (pinned by scripts/threejs_viewer/package-lock.json) renders it in
// headless Chromium, from a page served on 127.0.0.1, and the screenshot is checked.
//
// The model is a flat 4 x 3 m plane in the model's x-y (z up, +Y north), textured red in the north-west
// quadrant, green north-east, blue south-west and white south-east. scripts/threejs_viewer/render.html looks
// straight down glTF's -Y with glTF's -Z at the top of the screen, so a GLB that stands the model up as glTF
// asks (+Y up, north on -Z) shows a 4:3 rectangle with those colours in those corners: seen from above (an
// edge-on plane would be a line), north up, east right, not mirrored, the texture's sRGB kept (unlit).
// The same GLB with its geometry compressed (EXT_meshopt_compression) must look the same.
//
// Skips when chromium, python3 (the HTTP server) or scripts/threejs_viewer/node_modules is absent
// (scripts/install_dependencies.sh installs them all).

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/headless_browser.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "texturing/gltf_export.h"
#include "texturing/textured_mesh.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

constexpr double kWidth = 4.0;   // east-west extent [m]
constexpr double kHeight = 3.0;  // north-south extent [m]
constexpr int kTexelsPerMetre = 10;
constexpr int kWindowWidth = 800, kWindowHeight = 600;

// The quadrants' colours (8-bit sRGB, also linear: 0 and 1 are the same in both).
const cv::Vec3b kNorthWest(255, 0, 0), kNorthEast(0, 255, 0), kSouthWest(0, 0, 255), kSouthEast(255, 255, 255);

fs::path ViewerDir() { return fs::path(LUTEX_SOURCE_DIR) / "scripts" / "threejs_viewer"; }

// The plane, two faces facing up (+Z), on one page whose texel rows run from north (row 0) to south.
TexturedMesh QuadrantPlane() {
  TexturedMesh textured;
  textured.mesh.vertices = {{0, 0, 0}, {kWidth, 0, 0}, {kWidth, kHeight, 0}, {0, kHeight, 0}};
  textured.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  const int cols = int(kWidth) * kTexelsPerMetre, rows = int(kHeight) * kTexelsPerMetre;
  cv::Mat page(rows, cols, CV_32FC3);
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const bool north = row < rows / 2, east = col >= cols / 2;
      const cv::Vec3b colour = north ? (east ? kNorthEast : kNorthWest) : (east ? kSouthEast : kSouthWest);
      page.at<cv::Vec3f>(row, col) = cv::Vec3f(colour[0] / 255.0f, colour[1] / 255.0f, colour[2] / 255.0f);  // RGB
    }
  }
  textured.pages = {page};
  textured.face_page = {0, 0};
  textured.face_corner_texels.resize(2);
  for (std::size_t f = 0; f < 2; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = textured.mesh.vertices[textured.mesh.faces[f][k]];
      textured.face_corner_texels[f][k] = Eigen::Vector2f(float(v.x() * kTexelsPerMetre), float((kHeight - v.y()) * kTexelsPerMetre));
    }
  }
  return textured;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The screenshot of QuadrantPlane as render.html frames it: a 4:3 rectangle, centred, 90 % of the window
// wide (render.html's margin), each quadrant in its colour.
void ExpectThePlaneFromAbove(const cv::Mat& picture) {
  ASSERT_EQ(picture.cols, kWindowWidth);
  ASSERT_EQ(picture.rows, kWindowHeight);
  const cv::Rect bounds =
      testing::ExpectQuadrantsFromAbove(picture, kWidth / kHeight, {kNorthWest, kNorthEast, kSouthWest, kSouthEast}, "three.js");
  EXPECT_NEAR(bounds.x + 0.5 * bounds.width, 0.5 * kWindowWidth, 10.0) << "not centred";
  EXPECT_NEAR(bounds.y + 0.5 * bounds.height, 0.5 * kWindowHeight, 10.0) << "not centred";
  EXPECT_NEAR(double(bounds.width) / double(kWindowWidth), 0.9, 0.03) << "not framed to the window";
}

// Empty when the viewer can run here, else why not (a reason to skip).
std::string MissingViewer() {
  if (!testing::HaveProgram("chromium")) return "chromium is not installed (scripts/install_dependencies.sh)";
  if (!testing::HaveProgram("python3")) return "python3 is not installed (it serves the page)";
  if (!fs::exists(ViewerDir() / "node_modules" / "three" / "build" / "three.module.js")) {
    return "three.js is not installed in " + ViewerDir().string() + " (scripts/install_dependencies.sh)";
  }
  return "";
}

// Writes QuadrantPlane with `gltf`, renders it and checks the screenshot.
void ExpectTheGlbFromAbove(const GltfOptions& gltf) {
  // The served folder: the viewer's page and three.js (linked, not copied) beside the model.
  testing::TempDir dir;
  const fs::path site = dir.path() / "site";
  fs::create_directories(site);
  fs::create_symlink(ViewerDir() / "render.html", site / "render.html");
  fs::create_directory_symlink(ViewerDir() / "node_modules", site / "node_modules");
  WriteGltf(QuadrantPlane(), site / "model.glb", gltf);

  const fs::path server_log = dir.path() / "server.log";
  testing::LocalHttpServer server(site, server_log);
  ASSERT_NE(server.port(), 0) << "the HTTP server did not start: " << ReadText(server_log);

  const fs::path screenshot = dir.path() / "render.png";
  const std::string url = "http://127.0.0.1:" + std::to_string(server.port()) + "/render.html?model=/model.glb";
  const std::string browser = testing::TakeScreenshot(url, screenshot, kWindowWidth, kWindowHeight);
  const std::string diagnostics = "chromium:\n" + browser + "\nserver:\n" + ReadText(server_log);
  ASSERT_TRUE(fs::exists(screenshot)) << diagnostics;
  ASSERT_NE(browser.find("lutex-threejs: rendered"), std::string::npos) << "render.html did not render\n" << diagnostics;

  const cv::Mat picture = cv::imread(screenshot.string(), cv::IMREAD_COLOR);
  ExpectThePlaneFromAbove(picture);
  if (::testing::Test::HasFailure()) {
    const fs::path kept = fs::temp_directory_path() / "lutex_threejs_render_failed.png";
    fs::copy_file(screenshot, kept, fs::copy_options::overwrite_existing);
    std::cout << "the screenshot is kept as " << kept.string() << "\n" << diagnostics << "\n";
  }
}

TEST(ThreeJsRender, TheGlbIsSeenFromAboveNorthUpInItsColours) {
  if (const std::string missing = MissingViewer(); !missing.empty()) GTEST_SKIP() << missing;
  ExpectTheGlbFromAbove(GltfOptions{});
}

TEST(ThreeJsRender, AMeshoptCompressedGlbLooksTheSame) {
  if (const std::string missing = MissingViewer(); !missing.empty()) GTEST_SKIP() << missing;
  GltfOptions gltf;
  gltf.meshopt_compression = true;
  ExpectTheGlbFromAbove(gltf);
}

}  // namespace
}  // namespace lutex
