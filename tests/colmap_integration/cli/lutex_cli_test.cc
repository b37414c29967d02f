// The `lutex` binary as a user runs it: outputs where promised, identical at any thread count, and for
// bad input one line naming the file and the problem, a non-zero exit, and nothing written.

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/colmap_array.h"
#include "colmap_integration/io/sparse_model_binary.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geometry/mesh_primitives.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// Three 64x48 pinhole images looking straight down at the plane z = 0 from 2, 2.5 and 3 m.
void MakeWorkspace(const fs::path& root, SparseFormat format) {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 64, 48, 40.0, 40.0);
  for (std::uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "sub/img" + std::to_string(id) + ".jpg";
    image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.3 * id, 0, 1.5 + 0.5 * id),
                                                 Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
    model.images[id] = image;
  }
  WriteSparseModel(model, root / "sparse" / "0", format);
  WriteMesh(MakeHeightFieldMesh([](double, double) { return 0.0; }, -20, 20, -20, 20, 2, 2), root / "plane.ply");
}

std::string Raycast(const fs::path& root, const std::string& extra = "") {
  return std::string(LUTEX_BINARY) + " raycast --workspace " + root.string() + " --mesh " +
         (root / "plane.ply").string() + " " + extra;
}

TEST(LutexCli, RaycastWritesDepthNormalsAndPreviews) {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), SparseFormat::kBinary);
  const testing::CommandResult result = testing::RunCommand(Raycast(dir.path()));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const fs::path output = dir.path() / "lutex" / "raycast";
  EXPECT_NE(result.output.find((output / "depth_maps").string()), std::string::npos) << result.output;
  for (int id = 1; id <= 3; ++id) {
    const std::string name = "sub/img" + std::to_string(id) + ".jpg";
    const cv::Mat depth = ReadColmapArray(output / "depth_maps" / (name + ".geometric.bin"));
    ASSERT_EQ(depth.cols, 64);
    // Looking straight down at z = 0 from height h: every pixel's planar depth is h.
    double lowest, highest;
    cv::minMaxIdx(depth, &lowest, &highest);
    EXPECT_NEAR(lowest, 1.5 + 0.5 * id, 1e-5);
    EXPECT_NEAR(highest, 1.5 + 0.5 * id, 1e-5);
    const cv::Mat normal = ReadColmapArray(output / "normal_maps" / (name + ".geometric.bin"));
    EXPECT_NEAR(normal.at<cv::Vec3f>(10, 10)[2], -1.0f, 1e-6f);
    EXPECT_TRUE(fs::exists(output / "previews" / (name + ".depth.png")));
  }
}

TEST(LutexCli, OutputsDoNotDependOnTheThreadCount) {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), SparseFormat::kText);
  ASSERT_EQ(testing::RunCommand(Raycast(dir.path(), "--num-threads 1 --output " + (dir.path() / "one").string())).exit_code, 0);
  ASSERT_EQ(testing::RunCommand(Raycast(dir.path(), "--num-threads 2 --output " + (dir.path() / "two").string())).exit_code, 0);
  const auto read = [](const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
  };
  for (const char* map : {"depth_maps", "normal_maps"}) {
    const fs::path relative = fs::path(map) / "sub" / "img2.jpg.geometric.bin";
    EXPECT_EQ(read(dir.path() / "one" / relative), read(dir.path() / "two" / relative)) << map;
  }
}

// A malformed number names its option and value (not the C++ conversion function).
TEST(LutexCli, MalformedNumberNamesTheOption) {
  const testing::CommandResult result = testing::RunCommand(
      std::string(LUTEX_BINARY) + " calibrate --workspace W --mesh M.ply --targets T.json --z-near 0,5");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("--z-near expects a number, not '0,5'"), std::string::npos) << result.output;
}

// Correspondences without any known colour leave one factor per channel open: the error says what fixes it.
TEST(LutexCli, SelfCalibrationWithoutAScaleSaysWhatToGive) {
  const testing::CommandResult result =
      testing::RunCommand(std::string(LUTEX_BINARY) + " calibrate --workspace W --mesh M.ply --correspondences");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("--grey-world"), std::string::npos) << result.output;
  const testing::CommandResult neither =
      testing::RunCommand(std::string(LUTEX_BINARY) + " calibrate --workspace W --mesh M.ply");
  EXPECT_EQ(neither.exit_code, 1);
  EXPECT_NE(neither.output.find("give --targets or --chessboard (known colours), --correspondences (self-calibration), or both"),
            std::string::npos) << neither.output;
  const testing::CommandResult bad_grey = testing::RunCommand(
      std::string(LUTEX_BINARY) + " calibrate --workspace W --mesh M.ply --correspondences --grey-world 0.3,0.3");
  EXPECT_EQ(bad_grey.exit_code, 1);
  EXPECT_NE(bad_grey.output.find("--grey-world expects a number or x,y,z"), std::string::npos) << bad_grey.output;
}

// A board file that is missing or not JSON: one line naming it, nothing written.
TEST(LutexCli, BadBoardFileIsNamed) {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), SparseFormat::kBinary);
  fs::create_directories(dir.path() / "board_images");
  std::ofstream(dir.path() / "not_json.json") << "{chessboard";
  for (const auto& [file, problem] : {std::make_pair(std::string("absent.json"), std::string("no such board file")),
                                      std::make_pair(std::string("not_json.json"), std::string("not a board file"))}) {
    const fs::path board = dir.path() / file;
    const testing::CommandResult result = testing::RunCommand(
        std::string(LUTEX_BINARY) + " calibrate --workspace " + dir.path().string() + " --mesh " +
        (dir.path() / "plane.ply").string() + " --chessboard " + board.string() + " --chessboard-images " +
        (dir.path() / "board_images").string() + " --output " + (dir.path() / "out.lut").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(board.string() + ": " + problem), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir.path() / "out.lut"));
  }
}

TEST(LutexCli, HelpTeachesTheOptions) {
  const testing::CommandResult result = testing::RunCommand(std::string(LUTEX_BINARY) + " raycast --help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("--workspace"), std::string::npos);
  EXPECT_NE(result.output.find("--num-threads"), std::string::npos);
  EXPECT_EQ(testing::RunCommand(std::string(LUTEX_BINARY) + " --help").exit_code, 0);
  EXPECT_NE(testing::RunCommand(std::string(LUTEX_BINARY) + " frobnicate").exit_code, 0);
}

// Runs raycast on a workspace broken by `breakage` and expects one error line containing each of
// `expected_parts`, a non-zero exit and no W/lutex folder.
void ExpectCleanFailure(SparseFormat format, const std::function<void(const fs::path&)>& breakage,
                        const std::vector<std::string>& expected_parts, const std::string& extra = "") {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), format);
  breakage(dir.path());
  const testing::CommandResult result = testing::RunCommand(Raycast(dir.path(), extra));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  std::string error_lines;
  std::istringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("error") != std::string::npos) error_lines += line + "\n";
  }
  EXPECT_EQ(std::count(error_lines.begin(), error_lines.end(), '\n'), 1) << result.output;
  for (const std::string& part : expected_parts) EXPECT_NE(error_lines.find(part), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "lutex")) << "something was written";
}

TEST(LutexCli, MissingImagesBin) {
  ExpectCleanFailure(SparseFormat::kBinary, [](const fs::path& root) { fs::remove(root / "sparse/0/images.bin"); },
                     {"images.bin", "no such file"});
}

TEST(LutexCli, TruncatedImagesBin) {
  ExpectCleanFailure(SparseFormat::kBinary,
                     [](const fs::path& root) {
                       const fs::path images = root / "sparse/0/images.bin";
                       fs::resize_file(images, fs::file_size(images) / 2);
                     },
                     {"images.bin", "truncated"});
}

TEST(LutexCli, ImageNamingAnUndefinedCamera) {
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) {
                       std::ofstream(root / "sparse/0/images.txt") << "7 1 0 0 0 0 0 2 9 a.jpg\n\n";
                     },
                     {"images.txt", "image 7", "names camera 9"});
}

TEST(LutexCli, CameraParameterCountMismatch) {
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) { std::ofstream(root / "sparse/0/cameras.txt") << "1 PINHOLE 64 48 40 40 32\n"; },
                     {"cameras.txt", "line 1", "takes 4 parameters"});
}

// Faults are reported against the file that holds them, not against images.bin.
TEST(LutexCli, EachFaultNamesTheFileThatHoldsIt) {
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) { std::ofstream(root / "sparse/0/cameras.txt") << "1 PINHOLE 64 48 0 40 32 24\n"; },
                     {"cameras.txt", "camera 1 has a focal length that is not positive"});
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) { std::ofstream(root / "sparse/0/cameras.txt") << "1 PINHOLE 0 48 40 40 32 24\n"; },
                     {"cameras.txt", "empty image size 0x48"});
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) {
                       std::ofstream(root / "sparse/0/points3D.txt") << "5 0 0 0 128 128 128 0.5 42 0\n";
                     },
                     {"points3D.txt", "3-D point 5 names image 42"});
}

// A size field corrupted to a huge value is a format error, not 3 GB of maps.
TEST(LutexCli, CameraSizeBeyondAnySensorIsAFormatError) {
  ExpectCleanFailure(SparseFormat::kText,
                     [](const fs::path& root) {
                       std::ofstream(root / "sparse/0/cameras.txt") << "1 PINHOLE 2147483648 48 40 40 32 24\n";
                     },
                     {"cameras.txt", "2147483648x48, beyond 100000 pixels a side"});
}

// Data after what a file declares means a wrong count or damage: refused, not ignored.
TEST(LutexCli, DataBeyondWhatAFileDeclaresIsRefused) {
  ExpectCleanFailure(SparseFormat::kBinary,
                     [](const fs::path& root) { std::ofstream(root / "sparse/0/images.bin", std::ios::app) << "trailing"; },
                     {"images.bin", "data after the last of the 3 images"});
  ExpectCleanFailure(SparseFormat::kBinary,
                     [](const fs::path& root) {
                       std::ofstream(root / "plane.ply", std::ios::app | std::ios::binary) << std::string(13, '\1');
                     },
                     {"plane.ply", "more data than its header declares"});
}

TEST(LutexCli, MeshThatIsNotAMesh) {
  ExpectCleanFailure(SparseFormat::kBinary,
                     [](const fs::path& root) { std::ofstream(root / "plane.ply") << "GIF89a not a mesh"; },
                     {"plane.ply", "not a PLY file"});
}

// A thread count below 0 or beyond 4 per core is a typo, refused before anything is read.
TEST(LutexCli, ThreadCountOutsideZeroToFourPerCoreIsRefused) {
  ExpectCleanFailure(SparseFormat::kBinary, [](const fs::path&) {}, {"--num-threads must be from 0 to", "not -3"},
                     "--num-threads -3");
  ExpectCleanFailure(SparseFormat::kBinary, [](const fs::path&) {}, {"--num-threads must be from 0 to", "not 100000"},
                     "--num-threads 100000");
}

TEST(LutexCli, UnknownOptionAndMissingWorkspace) {
  ExpectCleanFailure(SparseFormat::kBinary, [](const fs::path&) {}, {"unknown option --colour"}, "--colour red");
  ExpectCleanFailure(SparseFormat::kBinary, [](const fs::path& root) { fs::remove_all(root / "sparse"); },
                     {"no COLMAP sparse model"});
}

}  // namespace
}  // namespace lutex
