// lutex's GLB in a real viewer: three.js (pinned by scripts/threejs_viewer/package-lock.json) renders it in
// headless Chromium, from a page served on 127.0.0.1, and the screenshot is checked.
//
// The model is a flat 4 x 3 m plane in the model's x-y (z up, +Y north), textured red in the north-west
// quadrant, green north-east, blue south-west and white south-east. scripts/threejs_viewer/render.html looks
// straight down glTF's -Y with glTF's -Z at the top of the screen, so a GLB that stands the model up as glTF
// asks (+Y up, north on -Z) shows a 4:3 rectangle with those colours in those corners: seen from above (an
// edge-on plane would be a line), north up, east right, not mirrored, the texture's sRGB kept (unlit).
//
// Skips when chromium, python3 (the HTTP server) or scripts/threejs_viewer/node_modules is absent
// (scripts/install_dependencies.sh installs them all).

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
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

// Python's static file server on 127.0.0.1, on a port the system picks, serving `root` until destroyed.
// Its request log goes to `log`.
class LocalHttpServer {
 public:
  LocalHttpServer(const fs::path& root, const fs::path& log) {
    const std::string script =
        "import functools, http.server, sys\n"
        "handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=sys.argv[1])\n"
        "server = http.server.ThreadingHTTPServer(('127.0.0.1', 0), handler)\n"
        "print(server.server_address[1], flush=True)\n"
        "server.serve_forever()\n";
    std::vector<std::string> arguments = {"python3", "-c", script, root.string()};
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    int pipe_ends[2];
    if (pipe(pipe_ends) != 0) return;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 1);
    posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
    posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
    close(pipe_ends[1]);
    // The first line is the port; end of file (the server died) leaves port_ at 0.
    FILE* output = fdopen(pipe_ends[0], "r");
    std::array<char, 32> line{};
    if (pid_ != 0 && fgets(line.data(), int(line.size()), output)) port_ = std::atoi(line.data());
    fclose(output);
  }
  ~LocalHttpServer() {
    if (pid_ == 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  LocalHttpServer(const LocalHttpServer&) = delete;
  LocalHttpServer& operator=(const LocalHttpServer&) = delete;

  int port() const { return port_; }  // 0 when it did not start

 private:
  pid_t pid_ = 0;
  int port_ = 0;
};

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The share of `pixels` within `tolerance` of `expected` (RGB) in every channel; `pixels` is OpenCV's BGR.
double ShareNear(const cv::Mat& pixels, const cv::Vec3b& expected, int tolerance) {
  int near = 0;
  for (int row = 0; row < pixels.rows; ++row) {
    for (int col = 0; col < pixels.cols; ++col) {
      const cv::Vec3b bgr = pixels.at<cv::Vec3b>(row, col);
      near += std::abs(bgr[2] - expected[0]) <= tolerance && std::abs(bgr[1] - expected[1]) <= tolerance &&
              std::abs(bgr[0] - expected[2]) <= tolerance;
    }
  }
  return double(near) / double(pixels.total());
}

// The screenshot of QuadrantPlane as render.html frames it: a 4:3 rectangle, centred, 90 % of the window
// wide (render.html's margin), each quadrant in its colour.
void ExpectThePlaneFromAbove(const cv::Mat& picture) {
  ASSERT_EQ(picture.cols, kWindowWidth);
  ASSERT_EQ(picture.rows, kWindowHeight);

  // The model: whatever is not the black background.
  cv::Mat model_mask;
  cv::inRange(picture, cv::Scalar(0, 0, 0), cv::Scalar(30, 30, 30), model_mask);
  cv::bitwise_not(model_mask, model_mask);
  const double covered = double(cv::countNonZero(model_mask)) / double(picture.total());
  std::vector<cv::Point> model_pixels;
  cv::findNonZero(model_mask, model_pixels);
  ASSERT_FALSE(model_pixels.empty()) << "the screenshot is black";
  const cv::Rect bounds = cv::boundingRect(model_pixels);
  std::cout << "three.js render: the model covers " << 100.0 * covered << " % of the window, bounds " << bounds.width
            << " x " << bounds.height << " px at (" << bounds.x << ", " << bounds.y << ")\n";
  EXPECT_GT(covered, 0.2);
  EXPECT_NEAR(double(bounds.width) / double(bounds.height), kWidth / kHeight, 0.1) << "not seen from straight above";
  EXPECT_GT(double(cv::countNonZero(model_mask(bounds))) / double(bounds.area()), 0.95) << "not a rectangle";
  EXPECT_NEAR(bounds.x + 0.5 * bounds.width, 0.5 * kWindowWidth, 10.0) << "not centred";
  EXPECT_NEAR(bounds.y + 0.5 * bounds.height, 0.5 * kWindowHeight, 10.0) << "not centred";
  EXPECT_NEAR(double(bounds.width) / double(kWindowWidth), 0.9, 0.03) << "not framed to the window";

  // Each quadrant of the bounds in its colour: north up, east right, not mirrored.
  const int half_width = bounds.width / 2, half_height = bounds.height / 2;
  const struct {
    const char* name;
    cv::Rect quadrant;
    cv::Vec3b colour;
  } quadrants[] = {
      {"north-west (top left, red)", {bounds.x, bounds.y, half_width, half_height}, kNorthWest},
      {"north-east (top right, green)", {bounds.x + half_width, bounds.y, half_width, half_height}, kNorthEast},
      {"south-west (bottom left, blue)", {bounds.x, bounds.y + half_height, half_width, half_height}, kSouthWest},
      {"south-east (bottom right, white)", {bounds.x + half_width, bounds.y + half_height, half_width, half_height}, kSouthEast},
  };
  for (const auto& [name, quadrant, colour] : quadrants) {
    const double share = ShareNear(picture(quadrant), colour, 40);
    std::cout << "  " << name << ": " << 100.0 * share << " % in its colour\n";
    EXPECT_GT(share, 0.9) << name;
  }
}

TEST(ThreeJsRender, TheGlbIsSeenFromAboveNorthUpInItsColours) {
  if (!testing::HaveProgram("chromium")) GTEST_SKIP() << "chromium is not installed (scripts/install_dependencies.sh)";
  if (!testing::HaveProgram("python3")) GTEST_SKIP() << "python3 is not installed (it serves the page)";
  if (!fs::exists(ViewerDir() / "node_modules" / "three" / "build" / "three.module.js")) {
    GTEST_SKIP() << "three.js is not installed in " << ViewerDir().string() << " (scripts/install_dependencies.sh)";
  }

  // The served folder: the viewer's page and three.js (linked, not copied) beside the model.
  testing::TempDir dir;
  const fs::path site = dir.path() / "site";
  fs::create_directories(site);
  fs::create_symlink(ViewerDir() / "render.html", site / "render.html");
  fs::create_directory_symlink(ViewerDir() / "node_modules", site / "node_modules");
  WriteGltf(QuadrantPlane(), site / "model.glb");

  const fs::path server_log = dir.path() / "server.log";
  LocalHttpServer server(site, server_log);
  ASSERT_NE(server.port(), 0) << "the HTTP server did not start: " << ReadText(server_log);

  // SwiftShader (software WebGL): headless Chromium has no GPU. The virtual time budget lets the page load
  // the model and draw before the screenshot is taken; the window takes its full --window-size only then
  // (render.html draws again on the resize). The page's console comes out in Chromium's log.
  const fs::path screenshot = dir.path() / "render.png";
  const std::string url = "http://127.0.0.1:" + std::to_string(server.port()) + "/render.html?model=/model.glb";
  const testing::CommandResult browser = testing::RunCommand(
      "timeout 60 chromium --headless --no-sandbox --disable-dev-shm-usage --disable-background-networking "
      "--no-first-run --hide-scrollbars --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--run-all-compositor-stages-before-draw --virtual-time-budget=10000 --enable-logging=stderr --v=0 "
      "--window-size=" + std::to_string(kWindowWidth) + "," + std::to_string(kWindowHeight) +
      " --screenshot=" + screenshot.string() + " '" + url + "'");
  const std::string diagnostics = "chromium:\n" + browser.output + "\nserver:\n" + ReadText(server_log);
  ASSERT_TRUE(fs::exists(screenshot)) << diagnostics;
  ASSERT_NE(browser.output.find("lutex-threejs: rendered"), std::string::npos) << "render.html did not render\n" << diagnostics;

  const cv::Mat picture = cv::imread(screenshot.string(), cv::IMREAD_COLOR);
  ExpectThePlaneFromAbove(picture);
  if (HasFailure()) {
    const fs::path kept = fs::temp_directory_path() / "lutex_threejs_render_failed.png";
    fs::copy_file(screenshot, kept, fs::copy_options::overwrite_existing);
    std::cout << "the screenshot is kept as " << kept.string() << "\n" << diagnostics << "\n";
  }
}

}  // namespace
}  // namespace lutex
