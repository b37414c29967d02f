// `lutex run` end to end on a small version of the bundled example (examples/dive: a survey of a synthetic
// seafloor, frames of a colour board and of pure water, all made by lutex simulate):
//   - the restored images match the simulator's true albedo, the GLB validates, the report is written and
//     headless Chromium renders it;
//   - a second run (another --image-cache) finds everything up to date and rewrites nothing; a texture
//     option redoes the texture only;
//   - a run killed (SIGKILL) inside calibrate, inside restore and inside texture, then started again, ends
//     with outputs identical, byte for byte, to those of the uninterrupted run.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colmap_integration/stages/simulate_workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "tests/support/charuco_board.h"
#include "tests/support/gltf_validator.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

extern char** environ;

namespace lutex {
namespace {

namespace fs = std::filesystem;

const fs::path kExample = fs::path(LUTEX_SOURCE_DIR) / "examples";

// The example's scene `source` at 320 x 240 (and the survey shortened), written to `destination`.
void WriteSmallScene(const fs::path& source, const fs::path& destination, std::size_t keep_every) {
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(source));
  scene["camera"]["width"] = 320;
  scene["camera"]["height"] = 240;
  scene["camera"]["params"] = {160, 160, 160, 120};
  if (scene.contains("mesh") && scene["mesh"].is_string()) {
    scene["mesh"] = (source.parent_path() / scene["mesh"].get<std::string>()).string();
  }
  if (scene.contains("survey")) {
    scene["survey"]["lines"] = 2;
    scene["survey"]["images_per_line"] = 5;
  }
  if (scene.contains("poses")) {
    nlohmann::json kept = nlohmann::json::array();
    for (std::size_t i = 0; i < scene["poses"].size(); i += keep_every) kept.push_back(scene["poses"][i]);
    scene["poses"] = kept;
  }
  std::ofstream(destination) << scene.dump(1);
}

fs::path Simulate(const fs::path& scene, const fs::path& output) {
  SimulateOptions options;
  options.scene = scene;
  options.output = output;
  SimulateWorkspace(options);
  return output;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Every file under `folder` (relative path -> bytes), without what holds times: the run records, the
// report, and the solve time in the calibration summary.
std::map<std::string, std::string> Outputs(const fs::path& folder) {
  std::map<std::string, std::string> outputs;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string relative = fs::relative(entry.path(), folder).string();
    if (!entry.is_regular_file() || relative.rfind("run/", 0) == 0 || relative.rfind("report/", 0) == 0) continue;
    if (entry.path().filename() == "calibration_summary.json") {
      nlohmann::json summary = nlohmann::json::parse(std::ifstream(entry.path()));
      summary.erase("seconds");
      outputs[relative] = summary.dump();
    } else {
      outputs[relative] = ReadBytes(entry.path());
    }
  }
  return outputs;
}

// Restored albedo (W/lutex/restored, 8-bit sRGB) against the simulator's truth, over pixels with a surface
// and channels, in percentage points.
double RestoredAlbedoError(const fs::path& workspace) {
  double error_sum = 0.0;
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(workspace / "ground_truth" / "albedo")) {
    const cv::Mat truth = ReadLinearImage(entry.path(), ImageEncoding::kLinear16);
    const cv::Mat restored = ReadLinearImage(workspace / "lutex" / "restored" / entry.path().filename(), ImageEncoding::kSrgb8);
    for (int y = 0; y < truth.rows; ++y) {
      for (int x = 0; x < truth.cols; ++x) {
        const cv::Vec3f t = truth.at<cv::Vec3f>(y, x);
        if (t[0] + t[1] + t[2] <= 0.0f) continue;
        const cv::Vec3f r = restored.at<cv::Vec3f>(y, x);
        for (int c = 0; c < 3; ++c) error_sum += std::abs(double(r[c]) - double(t[c]));
        count += 3;
      }
    }
  }
  EXPECT_GT(count, 0u);
  return 100.0 * error_sum / double(std::max<std::size_t>(count, 1));
}

class RunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new testing::TempDir();
    const fs::path root = data_->path();
    WriteSmallScene(kExample / "scenes" / "clear_two_lights.json", root / "survey.json", 1);
    WriteSmallScene(kExample / "dive" / "board.json", root / "board.json", 3);
    WriteSmallScene(kExample / "dive" / "purewater.json", root / "purewater.json", 2);
    Simulate(root / "survey.json", root / "survey");
    Simulate(root / "board.json", root / "board");
    Simulate(root / "purewater.json", root / "purewater");
  }
  static void TearDownTestSuite() {
    delete data_;
    data_ = nullptr;
  }

  // A fresh copy of the simulated survey workspace (images, model, mesh) in `folder`.
  static fs::path CopyOfSurvey(const fs::path& folder) {
    fs::copy(data_->path() / "survey", folder, fs::copy_options::recursive);
    return folder;
  }

  static std::vector<std::string> RunArguments(const fs::path& workspace) {
    const fs::path root = data_->path();
    return {LUTEX_BINARY, "run", "--workspace", workspace.string(), "--mesh", (workspace / "scene" / "mesh.ply").string(),
            "--targets", (kExample / "dive" / "board_targets.json").string(),
            "--targets-workspace", (root / "board").string(),
            "--targets-mesh", (root / "board" / "scene" / "mesh.ply").string(),
            "--pure-water", (root / "purewater").string(),
            "--lut-nx", "20", "--lut-ny", "15", "--lut-nz", "8", "--num-threads", "2", "--log-level", "warning"};
  }

  static testing::CommandResult Run(const fs::path& workspace, const std::string& extra = "") {
    std::string command;
    for (const std::string& argument : RunArguments(workspace)) command += "'" + argument + "' ";
    return testing::RunCommand(command + extra);
  }

  // Frames of a board (its mesh at `board_mesh`: centred on the world origin in z = 0, printed side up)
  // taken with the example's rig looking down from 1.2-2.5 m, the board in the centre and the four
  // quadrants of the image; `lutex run` calibrates from them (board file `board_file`) and the pure water
  // and restores a copy of the survey. Expects the board found in at least 14 of the 20 frames and the
  // restored albedo within 6 pp MAE; `board_name` labels the printed numbers.
  static void ExpectBoardFramesCalibrateTheSurvey(const fs::path& dir, const fs::path& board_mesh,
                                                  const fs::path& board_file, const std::string& board_name) {
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(data_->path() / "board.json"));
    scene["mesh"] = board_mesh.string();
    scene["poses"] = nlohmann::json::array();
    for (const double height : {1.2, 1.6, 2.0, 2.5}) {
      for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {0.35, 0.25}, {-0.35, 0.25}, {0.35, -0.25}, {-0.35, -0.25}}) {
        // Looking straight down from (x h, y h, h): cam_from_world rotation diag(1, -1, -1).
        scene["poses"].push_back({{"name", "board_" + std::to_string(scene["poses"].size()) + ".png"},
                                  {"qvec", {0, 1, 0, 0}},
                                  {"tvec", {-x * height, y * height, height}}});
      }
    }
    std::ofstream(dir / "board_frames.json") << scene.dump(1);
    Simulate(dir / "board_frames.json", dir / "board_frames");
    const fs::path workspace = CopyOfSurvey(dir / "W");
    const testing::CommandResult run = testing::RunCommand(
        std::string(LUTEX_BINARY) + " run --workspace " + workspace.string() + " --mesh " +
        (workspace / "scene" / "mesh.ply").string() + " --chessboard " + board_file.string() +
        " --chessboard-images " + (dir / "board_frames" / "images").string() + " --pure-water " +
        (data_->path() / "purewater").string() + " --lut-nx 20 --lut-ny 15 --lut-nz 8 --num-threads 2 --no-report");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const nlohmann::json summary =
        nlohmann::json::parse(std::ifstream(workspace / "lutex" / "calibration" / "calibration_summary.json"));
    const int found = summary.at("chessboard_images").get<int>();
    std::cout << board_name << " found in " << found << " of 20 frames\n";
    EXPECT_GE(found, 14);
    const double mae = RestoredAlbedoError(workspace);
    std::cout << "lutex run from a " << board_name << ": restored albedo MAE " << mae << " pp\n";
    EXPECT_LT(mae, 6.0);
  }

  static testing::TempDir* data_;
};

testing::TempDir* RunTest::data_ = nullptr;

// Starts `lutex run`, waits until `ready` says the stage is under way, kills the process with SIGKILL.
// Returns true when the kill landed (the run had not finished by itself).
bool KillRunWhen(const std::vector<std::string>& arguments, const std::function<bool()>& ready) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return false;  // finished before the stage was reached
    if (ready()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

bool StageStarted(const fs::path& workspace, const std::string& stage) {
  return ReadBytes(workspace / "lutex" / "run" / (stage + ".json")).find("\"state\": \"started\"") != std::string::npos;
}

std::size_t FilesIn(const fs::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) return 0;
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// Lines of `output` that say `mesh` was read (the debug log of ReadMesh).
int TimesMeshWasRead(const std::string& output, const fs::path& mesh) {
  const std::string line = "read mesh " + mesh.string() + ":";
  int count = 0;
  for (std::size_t at = output.find(line); at != std::string::npos; at = output.find(line, at + 1)) ++count;
  return count;
}

// The stages (raycast, calibrate, restore, texture, mosaic, tiles) share the dive `lutex run` loads: the
// survey's mesh is not read once per stage, only again after a stage that freed it, and the mesh of the
// separate target images is read once. The model is georeferenced here, so the tiles stage runs.
TEST_F(RunTest, StagesShareTheLoadedDiveUntilOneFreesItsMesh) {
  testing::TempDir dir;
  const fs::path workspace = CopyOfSurvey(dir.path() / "W");
  const testing::CommandResult run =
      Run(workspace, "--depth-maps --no-report --log-level debug --enu-origin 54.32,10.14,-20 --tile-faces 20000");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(workspace / "lutex" / "tiles" / "tileset.json"));
  for (const char* stage : {"raycast", "calibrate", "restore", "texture", "mosaic", "tiles"}) {
    EXPECT_NE(run.output.find(std::string("[") + stage + ": done"), std::string::npos) << stage;
  }
  // Once for the stages up to the mosaic, which frees it once it is on disk block by block, and once
  // more for the tiles, which free it the same way (loaded_dive.h ReleaseMesh).
  EXPECT_EQ(TimesMeshWasRead(run.output, workspace / "scene" / "mesh.ply"), 2) << run.output;
  EXPECT_EQ(TimesMeshWasRead(run.output, data_->path() / "board" / "scene" / "mesh.ply"), 1);
  // A georeferenced model's up is its frame's +z: the GLB and the tiles are turned to glTF's +Y from that.
  EXPECT_NE(run.output.find("up: +z of the model (the georeferenced frame's)"), std::string::npos) << run.output;
}

TEST_F(RunTest, RestoresTexturesReportsAndSkipsWhatIsUpToDate) {
  testing::TempDir dir;
  const fs::path workspace = CopyOfSurvey(dir.path() / "W");
  const testing::CommandResult first = Run(workspace);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("[calibrate: done"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("report:"), std::string::npos) << first.output;

  const double mae = RestoredAlbedoError(workspace);
  std::cout << "lutex run on the small example: restored albedo MAE " << mae << " pp\n";
  EXPECT_LT(mae, 5.0);

  EXPECT_TRUE(fs::exists(workspace / "lutex" / "mosaic" / "ortho.tif"));
  EXPECT_TRUE(fs::exists(workspace / "lutex" / "mosaic" / "dem.tif"));
  EXPECT_NE(first.output.find("[tiles: not needed]\ntiles: skipped: the model is not georeferenced"), std::string::npos)
      << first.output;
  EXPECT_FALSE(fs::exists(workspace / "lutex" / "tiles"));
  // The simulated seafloor is +Z up and the survey looks down: the GLB is turned to glTF's +Y from that.
  EXPECT_NE(first.output.find("up: +z of the model (opposite the cameras' mean viewing direction)"), std::string::npos)
      << first.output;
  const testing::GltfValidation validation = testing::ValidateGltf(workspace / "lutex" / "model.glb");
  if (validation.ran) {
    EXPECT_TRUE(validation.valid) << validation.output;
  }
  const std::string report = ReadBytes(workspace / "lutex" / "report" / "index.html");
  for (const char* part : {"<h2>Run</h2>", "<h2>Calibration</h2>", "water prior: attenuation of the signal", "The LUT",
                           "<h2>Restoration</h2>", "<h2>Texture</h2>", "<h2>Mosaic</h2>", "title=\"orthomosaic\"",
                           "title=\"DEM\"", "data:image/png;base64,", "data:image/jpeg;base64,", "<svg"}) {
    EXPECT_NE(report.find(part), std::string::npos) << part;
  }
  for (const char* fetch : {"src=\"http", "href=\"http", "url(http", "<script"}) {
    EXPECT_EQ(report.find(fetch), std::string::npos) << "the report must not need the network: " << fetch;
  }

  // In a real browser: headless Chromium renders the page with every picture (no network).
  if (!testing::HaveProgram("chromium")) {
    std::cout << "chromium is not installed (scripts/install_dependencies.sh installs it): report not rendered\n";
  } else {
    const fs::path screenshot = dir.path() / "report.png";
    const testing::CommandResult browser = testing::RunCommand(
        "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage "
        "--disable-background-networking --no-first-run --hide-scrollbars --window-size=1400,3000 --screenshot=" +
        screenshot.string() + " file://" + (workspace / "lutex" / "report" / "index.html").string());
    ASSERT_TRUE(fs::exists(screenshot)) << browser.output;
    const cv::Mat picture = cv::imread(screenshot.string(), cv::IMREAD_COLOR);
    ASSERT_EQ(picture.cols, 1400);
    ASSERT_EQ(picture.rows, 3000);
    // Not a blank or error page: the LUT's false colours and the photographs cover a good part of it.
    cv::Mat hsv;
    cv::cvtColor(picture, hsv, cv::COLOR_BGR2HSV);
    std::vector<cv::Mat> channels;
    cv::split(hsv, channels);
    const double coloured = double(cv::countNonZero(channels[1] > 80)) / double(picture.total());
    std::cout << "report screenshot: " << 100.0 * coloured << " % of the first 3000 px in colour\n";
    EXPECT_GT(coloured, 0.1);
  }

  // Nothing changed but how much the mosaic and tiles keep decoded: nothing is redone or rewritten.
  const auto model_time = fs::last_write_time(workspace / "lutex" / "model.glb");
  const auto lut_time = fs::last_write_time(workspace / "lutex" / "calibration" / "lut.lut");
  const testing::CommandResult second = Run(workspace, "--image-cache 0");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  for (const char* stage : {"calibrate", "restore", "texture", "mosaic"}) {
    EXPECT_NE(second.output.find(std::string("[") + stage + ": up to date"), std::string::npos) << second.output;
  }
  EXPECT_EQ(fs::last_write_time(workspace / "lutex" / "model.glb"), model_time);
  EXPECT_EQ(fs::last_write_time(workspace / "lutex" / "calibration" / "lut.lut"), lut_time);

  // A texture option redoes the texture only.
  const testing::CommandResult third = Run(workspace, "--blend single");
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("[calibrate: up to date"), std::string::npos) << third.output;
  EXPECT_NE(third.output.find("[restore: up to date"), std::string::npos) << third.output;
  EXPECT_NE(third.output.find("[texture: done"), std::string::npos) << third.output;
}

// A chessboard instead of the colour board: frames of a black-and-white chessboard (9 x 6 inner corners,
// 0.12 m squares, white margin) taken with the example's rig from 1.2-2.5 m, the board in the centre and
// the four quadrants of the image; lutex run calibrates from it and the pure water, and restores the survey.
TEST_F(RunTest, ChessboardFramesCalibrateTheSurvey) {
  testing::TempDir dir;
  const int corners_x = 9, corners_y = 6;
  const double square = 0.12;
  {
    std::ofstream ply(dir.path() / "chessboard.ply");
    const int squares_x = corners_x + 3, squares_y = corners_y + 3;  // with the margin
    ply << "ply\nformat ascii 1.0\nelement vertex " << 4 * squares_x * squares_y
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2 * squares_x * squares_y
        << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
           "end_header\n";
    for (int b = -2; b <= corners_y; ++b) {
      for (int a = -2; a <= corners_x; ++a) {
        const double x = (a - 0.5 * (corners_x - 1)) * square, y = (b - 0.5 * (corners_y - 1)) * square;
        ply << x << " " << y << " 0\n" << x + square << " " << y << " 0\n" << x + square << " " << y + square
            << " 0\n" << x << " " << y + square << " 0\n";
      }
    }
    int base = 0;
    for (int b = -2; b <= corners_y; ++b) {
      for (int a = -2; a <= corners_x; ++a, base += 4) {
        const bool margin = a == -2 || b == -2 || a == corners_x || b == corners_y;
        const int grey = margin || ((a + b) % 2 + 2) % 2 == 0 ? 225 : 25;
        ply << "3 " << base << " " << base + 1 << " " << base + 2 << " " << grey << " " << grey << " " << grey << "\n";
        ply << "3 " << base << " " << base + 2 << " " << base + 3 << " " << grey << " " << grey << " " << grey << "\n";
      }
    }
  }
  std::ofstream(dir.path() / "spec.json") << R"({"chessboard": {"inner_corners": [9, 6], "square_size": 0.12,
    "black_albedo_srgb8": [25, 25, 25], "white_albedo_srgb8": [225, 225, 225]}})";
  ExpectBoardFramesCalibrateTheSurvey(dir.path(), dir.path() / "chessboard.ply", dir.path() / "spec.json", "chessboard");
}

// The same with a ChArUco board of 6 x 4 squares of 0.2 m and six coloured patches (the board file written
// as a user would: squares, sizes, dictionary, patches in the board frame): the markers make the board
// found even where part of it is out of view.
TEST_F(RunTest, CharucoFramesWithColourPatchesCalibrateTheSurvey) {
  testing::TempDir dir;
  const CharucoSpec spec = testing::PatchedCharucoSpec(0.2);
  Mesh board = testing::CharucoBoardMesh(spec);
  // Centred on the origin; board y along world -y, so the printed side (board -z) faces the cameras above.
  for (Eigen::Vector3d& vertex : board.vertices) {
    vertex = Eigen::Vector3d(vertex.x() - 3 * spec.square_size, -(vertex.y() - 2 * spec.square_size), 0.0);
  }
  WriteMesh(board, dir.path() / "charuco.ply");
  nlohmann::json patches = nlohmann::json::array();
  for (const ColourPatch& patch : spec.patches) {
    patches.push_back({{"name", patch.name},
                       {"corners", {patch.min_in_board.x(), patch.min_in_board.y(), patch.max_in_board.x(), patch.max_in_board.y()}},
                       {"albedo_linear", {patch.albedo.x(), patch.albedo.y(), patch.albedo.z()}}});
  }
  std::ofstream(dir.path() / "charuco.json") << nlohmann::json{
      {"charuco", {{"squares", {6, 4}}, {"square_size", 0.2}, {"marker_size", 0.15}, {"dictionary", "DICT_4X4_50"},
                   {"black_albedo_srgb8", {25, 25, 25}}, {"patches", patches}}}}.dump(1);
  ExpectBoardFramesCalibrateTheSurvey(dir.path(), dir.path() / "charuco.ply", dir.path() / "charuco.json",
                                      "ChArUco board");
}

TEST_F(RunTest, BadInputFailsWithOneLineNamingItAndWritesNothing) {
  testing::TempDir dir;
  const fs::path workspace = CopyOfSurvey(dir.path() / "W");
  std::vector<std::string> arguments = RunArguments(workspace);
  const auto run_with = [&](const std::string& option, const std::string& value) {
    std::string command;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
      const bool replaced = i > 0 && arguments[i - 1] == option;
      command += "'" + (replaced ? value : arguments[i]) + "' ";
    }
    return testing::RunCommand(command);
  };
  const testing::CommandResult no_targets = run_with("--targets", (dir.path() / "missing.json").string());
  EXPECT_NE(no_targets.exit_code, 0);
  EXPECT_NE(no_targets.output.find("missing.json"), std::string::npos) << no_targets.output;
  const testing::CommandResult no_mesh = run_with("--mesh", (dir.path() / "missing.ply").string());
  EXPECT_NE(no_mesh.exit_code, 0);
  EXPECT_NE(no_mesh.output.find("missing.ply: no such mesh file"), std::string::npos) << no_mesh.output;
  const testing::CommandResult nothing = testing::RunCommand(std::string(LUTEX_BINARY) + " run --workspace " +
                                                             workspace.string() + " --mesh " +
                                                             (workspace / "scene" / "mesh.ply").string());
  EXPECT_NE(nothing.exit_code, 0);
  EXPECT_NE(nothing.output.find("nothing to calibrate from"), std::string::npos) << nothing.output;
  EXPECT_FALSE(fs::exists(workspace / "lutex"));
}

// One writer per workspace: a second run while the first is working is refused, naming the first one's pid;
// after the first is killed, its lock file is taken over with a warning and the run completes.
TEST_F(RunTest, ASecondRunOnABusyWorkspaceIsRefusedAndAKilledRunsLockIsTakenOver) {
  testing::TempDir dir;
  const fs::path workspace = CopyOfSurvey(dir.path() / "W");
  std::vector<std::string> arguments = RunArguments(workspace);
  arguments.push_back("--no-report");
  testing::CommandResult second;
  const bool killed = KillRunWhen(arguments, [&] {
    if (!StageStarted(workspace, "calibrate")) return false;
    second = Run(workspace, "--no-report");
    return true;
  });
  ASSERT_TRUE(killed) << "the first run ended before the second started";
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find(workspace.string() + " is in use by lutex pid "), std::string::npos) << second.output;
  EXPECT_EQ(std::count(second.output.begin(), second.output.end(), '\n'), 1) << second.output;
  ASSERT_TRUE(fs::exists(workspace / "lutex" / ".lock"));  // left by the killed run

  const testing::CommandResult third = Run(workspace, "--no-report");
  EXPECT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("ended without releasing it (killed or crashed); taking it over"), std::string::npos)
      << third.output;
  EXPECT_FALSE(fs::exists(workspace / "lutex" / ".lock"));  // released
}

TEST_F(RunTest, KilledInEveryStageAndStartedAgainEndsWithTheSameOutputs) {
  testing::TempDir dir;
  const fs::path reference = CopyOfSurvey(dir.path() / "reference");
  const fs::path killed = CopyOfSurvey(dir.path() / "killed");
  ASSERT_EQ(Run(reference).exit_code, 0);

  const std::vector<std::string> arguments = RunArguments(killed);
  EXPECT_TRUE(KillRunWhen(arguments, [&] {
    return StageStarted(killed, "calibrate");
  })) << "the run should have been killed while calibrating";
  EXPECT_TRUE(KillRunWhen(arguments, [&] {
    return StageStarted(killed, "restore") && FilesIn(killed / "lutex" / "restored") >= 3;
  })) << "the run should have been killed while restoring";
  const std::size_t restored_before = FilesIn(killed / "lutex" / "restored");
  KillRunWhen(arguments, [&] { return StageStarted(killed, "texture"); });

  const testing::CommandResult resumed = Run(killed);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_LT(restored_before, 10u) << "restore should have been cut off before it wrote all images";

  const auto expected = Outputs(reference / "lutex");
  const auto actual = Outputs(killed / "lutex");
  ASSERT_EQ(expected.size(), actual.size());
  for (const auto& [name, bytes] : expected) {
    ASSERT_EQ(actual.count(name), 1u) << name;
    EXPECT_TRUE(actual.at(name) == bytes) << name << " differs from the uninterrupted run's";
  }
}

}  // namespace
}  // namespace lutex
