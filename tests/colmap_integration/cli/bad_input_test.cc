// The README's "Bad input" table, case by case: a user's realistic mistakes and damaged files. Every case
// runs the real `lutex` binary on its own copy of a small simulated dive and asserts what the table
// promises:
//   - a non-zero exit;
//   - exactly one line on stderr, naming the file that is wrong (or the output and the input it would
//     destroy) and what is wrong with it;
//   - not one file added, removed or changed anywhere in the dive's folder (inputs and outputs alike).

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/simulate_workspace.h"
#include "lib/lut/lut_file.h"
#include "lib/util/file_lock.h"
#include "tests/support/run_command.h"
#include "tests/support/small_survey.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_scenes.h"
#include "tests/support/tree_snapshot.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// The dive every case starts from, made once: D/W a simulated survey (6 images of 160 x 120, text model,
// D/W/scene/mesh.ply), D/lut.lut (alpha 1, beta 0 everywhere: restoring with it is valid), D/targets.json,
// D/a_file (a plain file), D/lutex.conf (a valid config file).
const fs::path& PristineDive() {
  // A static, not a leaked pointer: each case runs in its own process, and the folder must go with it.
  static const testing::TempDir dir;
  static const bool made = [](const fs::path& root) {
    std::ofstream(root / "scene.json") << testing::SmallSurveyScene().dump(1);
    SimulateOptions simulate;
    simulate.scene = root / "scene.json";
    simulate.output = root / "W";
    SimulateWorkspace(simulate);
    fs::remove_all(root / "W" / "ground_truth");
    const FrustumLutGrid grid = testing::LutGrid(4, 3, 4, FrustumLutGrid().z_near, FrustumLutGrid().z_far, 160, 120);
    FrustumLut lut(grid);
    for (int n = 0; n < grid.NumNodes(); ++n) lut.node(n).alpha = Eigen::Vector3d::Ones();
    WriteLut(lut, root / "lut.lut");
    fs::copy_file(fs::path(LUTEX_SOURCE_DIR) / "examples" / "dive" / "board_targets.json", root / "targets.json");
    std::ofstream(root / "a_file") << "not a folder";
    std::ofstream(root / "lutex.conf") << "# a config file\nmesh = W/scene/mesh.ply\n";
    return true;
  }(dir.path());
  (void)made;
  return dir.path();
}

std::string ReadText(const fs::path& path) {
  std::ostringstream text;
  text << std::ifstream(path, std::ios::binary).rdbuf();
  return text.str();
}

void WriteText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Replaces the first `from` in the text file `path` with `to`.
void Edit(const fs::path& path, const std::string& from, const std::string& to) {
  std::string text = ReadText(path);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << path << " has no '" << from << "'";
  text.replace(at, from.size(), to);
  WriteText(path, text);
}

// The model of D/W in binary (cameras.bin, images.bin, points3D.bin) instead of text.
void MakeBinaryModel(const fs::path& dive) {
  const fs::path sparse = dive / "W" / "sparse" / "0";
  const SparseModel model = ReadSparseModel(sparse);
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt"}) fs::remove(sparse / name);
  WriteSparseModel(model, sparse, SparseFormat::kBinary);
}

void AppendBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::app) << bytes;
}

// The first line of the model's images.txt that describes an image (its pose line).
std::string FirstImageLine(const fs::path& dive) {
  std::istringstream lines(ReadText(dive / "W" / "sparse" / "0" / "images.txt"));
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] != '#') return line;
  }
  return {};
}

std::string FirstImageName(const fs::path& dive) {
  std::istringstream fields(FirstImageLine(dive));
  std::string field, name;
  while (fields >> field) name = field;
  return name;
}

struct BadInput {
  std::string name;                                // the gtest name
  std::function<void(const fs::path& dive)> make;  // breaks the copy D of the dive (may be empty)
  std::string command;                             // after "lutex"; {D} is the copy's folder
  std::string names;                               // what the line must name ({D} as above)
  std::string says;                                // and what it must say is wrong
};

std::string Expand(std::string text, const fs::path& dive) {
  for (std::size_t at; (at = text.find("{D}")) != std::string::npos;) text.replace(at, 3, dive.string());
  return text;
}

const std::string kDive = " --workspace {D}/W --mesh {D}/W/scene/mesh.ply";
const std::string kRestore = "restore" + kDive + " --lut {D}/lut.lut";
const std::string kCalibrate = "calibrate" + kDive + " --targets {D}/targets.json";

std::vector<BadInput> Cases() {
  return {
      // Outputs over or inside the inputs (output_policy.h).
      {"RestoreOverTheImages", {}, kRestore + " --output {D}/W/images", "{D}/W/images", "the output is the images"},
      {"RestoreInsideTheImages", {}, kRestore + " --output {D}/W/images/restored", "{D}/W/images",
       "the output lies inside the images"},
      {"RestoreIntoTheWorkspaceRoot", {}, kRestore + " --output {D}/W", "{D}/W/images", "the output contains"},
      {"RestoreThroughALinkToTheImages", [](const fs::path& d) { fs::create_directory_symlink(d / "W" / "images", d / "link"); },
       kRestore + " --output {D}/link/out", "{D}/W/images", "the output lies inside the images"},
      {"CalibrateOverTheTargetsFile", {}, kCalibrate + " --output {D}/targets.json", "{D}/targets.json",
       "the output is the targets file"},
      {"CalibrateIntoTheSparseModel", {}, kCalibrate + " --output {D}/W/sparse/0/lut.lut", "{D}/W/sparse/0",
       "lies inside the sparse model"},
      {"TextureOverTheMesh", {}, "texture" + kDive + " --output {D}/W/scene/mesh.ply", "{D}/W/scene/mesh.ply",
       "the output is the mesh"},
      // A textured PLY holds one atlas page: refused before any work when the area at the texel size cannot
      // fit (4 x 3 m at 1 mm is 12 Mtexels), and once packed, before any colour, when the charts do not.
      {"TexturedPlyTooLargeForOnePage", {}, "texture" + kDive + " --output {D}/out.ply --texel-size 0.001 --max-page-size 1024",
       "{D}/out.ply", "is a textured PLY, which holds one page; write a format without that limit, or raise --max-page-size"},
      // EXT_meshopt_compression exists only for .glb: refused before any work.
      {"MeshoptCompressionIntoGltfJson", {}, "texture" + kDive + " --output {D}/out.gltf --meshopt-compression", "{D}/out.gltf",
       "EXT_meshopt_compression (--meshopt-compression) is written into .glb files only"},
      {"TexturedPlyChartsOnManyPages", {}, "texture" + kDive + " --output {D}/out.ply --max-page-size 128 --log-level error",
       "{D}/out.ply",
       "pages of up to 128 texels, but"},
      {"RaycastIntoTheSparseModel", {}, "raycast" + kDive + " --output {D}/W/sparse/0", "{D}/W/sparse/0",
       "the output is the sparse model"},
      {"MosaicDemIntoTheImages", {}, "mosaic" + kDive + " --dem {D}/W/images/dem.tif", "{D}/W/images",
       "lies inside the images"},
      {"ReportIntoTheImages", {}, "report --workspace {D}/W --output {D}/W/images/report", "{D}/W/images",
       "lies inside the images"},
      {"OutputThroughAFile", {}, kRestore + " --output {D}/a_file/restored", "{D}/a_file", "is a file, not a folder"},
      {"RunWithItsMeshWhereItWritesTheModel",
       [](const fs::path& d) {
         fs::create_directories(d / "W" / "lutex");
         fs::copy_file(d / "W" / "scene" / "mesh.ply", d / "W" / "lutex" / "model.glb");
       },
       "run --workspace {D}/W --mesh {D}/W/lutex/model.glb --lut {D}/lut.lut",
       "{D}/W/lutex/model.glb", "the output is the mesh"},
      // Options and config files.
      {"NegativeThreadCount", {}, kRestore + " --num-threads -3", "--num-threads", "must be from 0 to"},
      {"HugeThreadCount", {}, kRestore + " --num-threads 100000", "--num-threads", "must be from 0 to"},
      {"MemoryLimitNotANumber", {}, kRestore + " --memory-limit lots", "--memory-limit", "must be a number of MiB"},
      {"UnknownReferenceWater", {}, kCalibrate + " --reference-water murky", "--reference-water",
       "must be auto, clear or coastal, not 'murky'"},
      {"EmptyMeshInAConfigFile", [](const fs::path& d) { WriteText(d / "lutex.conf", "# dive\nmesh =\n"); },
       "restore --workspace {D}/W --lut {D}/lut.lut --config {D}/lutex.conf", "{D}/lutex.conf:2", "--mesh has an empty value"},
      {"UnknownKeyInAConfigFile", [](const fs::path& d) { WriteText(d / "lutex.conf", "mesh = W/scene/mesh.ply\nlutt = x\n"); },
       "restore --workspace {D}/W --lut {D}/lut.lut --config {D}/lutex.conf", "{D}/lutex.conf:2", "lutt"},
      {"MissingConfigFile", {}, "restore --workspace {D}/W --lut {D}/lut.lut --config {D}/nowhere.conf",
       "{D}/nowhere.conf", "cannot read"},
      {"MeshAndWorkspaceForgotten", {}, "restore --lut {D}/lut.lut", "--workspace", "required"},
      // The sparse model.
      {"NoSparseModel", [](const fs::path& d) { fs::remove_all(d / "W" / "sparse"); }, kRestore, "{D}/W",
       "sparse"},
      {"CameraOfWidthZero", [](const fs::path& d) { Edit(d / "W" / "sparse" / "0" / "cameras.txt", "PINHOLE 160", "PINHOLE 0"); },
       kRestore, "{D}/W/sparse/0/cameras.txt", "camera 1"},
      {"CameraWithANanFocalLength", [](const fs::path& d) { Edit(d / "W" / "sparse" / "0" / "cameras.txt", "PINHOLE 160 120 80", "PINHOLE 160 120 nan"); },
       kRestore, "{D}/W/sparse/0/cameras.txt", "not a number"},
      {"CameraOfAnUnknownModel", [](const fs::path& d) { Edit(d / "W" / "sparse" / "0" / "cameras.txt", "PINHOLE", "PINHOLEY"); },
       kRestore, "{D}/W/sparse/0/cameras.txt", "PINHOLEY"},
      {"CameraSizeFieldCorrupted", [](const fs::path& d) { Edit(d / "W" / "sparse" / "0" / "cameras.txt", "PINHOLE 160", "PINHOLE 2147483648"); },
       kRestore, "{D}/W/sparse/0/cameras.txt", "beyond 100000 pixels"},
      {"ImageNamingAnUndefinedCamera",
       [](const fs::path& d) {
         std::istringstream fields(FirstImageLine(d));
         std::vector<std::string> f{std::istream_iterator<std::string>(fields), {}};
         std::string changed = f[0];
         for (std::size_t i = 1; i < f.size(); ++i) changed += " " + (i == 8 ? std::string("7") : f[i]);
         Edit(d / "W" / "sparse" / "0" / "images.txt", FirstImageLine(d), changed);
       },
       kRestore, "{D}/W/sparse/0/images.txt", "camera 7"},
      {"ImageWithANanPose",
       [](const fs::path& d) {
         const std::string line = FirstImageLine(d);
         const std::size_t first = line.find(' ');
         Edit(d / "W" / "sparse" / "0" / "images.txt", line, line.substr(0, first) + " nan" + line.substr(line.find(' ', first + 1)));
       },
       kRestore, "{D}/W/sparse/0/images.txt", "image"},
      {"PointNamingAnImageTheModelLacks",
       [](const fs::path& d) { WriteText(d / "W" / "sparse" / "0" / "points3D.txt", "5 0 0 0 128 128 128 0.5 42 0\n"); },
       kRestore, "{D}/W/sparse/0/points3D.txt", "image 42"},
      {"BytesAfterTheLastImageOfImagesBin",
       [](const fs::path& d) { MakeBinaryModel(d); AppendBytes(d / "W" / "sparse" / "0" / "images.bin", "junk"); },
       kRestore, "{D}/W/sparse/0/images.bin", "data after the last"},
      {"BytesAfterTheLastCameraOfCamerasBin",
       [](const fs::path& d) { MakeBinaryModel(d); AppendBytes(d / "W" / "sparse" / "0" / "cameras.bin", "junk"); },
       kRestore, "{D}/W/sparse/0/cameras.bin", "data after the last"},
      {"BytesAfterTheLastPointOfPoints3DBin",
       [](const fs::path& d) { MakeBinaryModel(d); AppendBytes(d / "W" / "sparse" / "0" / "points3D.bin", "junk"); },
       kRestore, "{D}/W/sparse/0/points3D.bin", "data after the last"},
      {"TruncatedImagesBin",
       [](const fs::path& d) {
         MakeBinaryModel(d);
         const fs::path path = d / "W" / "sparse" / "0" / "images.bin";
         fs::resize_file(path, fs::file_size(path) / 2);
       },
       kRestore, "{D}/W/sparse/0/images.bin", ""},
      // The mesh.
      {"MissingMesh", [](const fs::path& d) { fs::remove(d / "W" / "scene" / "mesh.ply"); }, kRestore,
       "{D}/W/scene/mesh.ply", "no such file"},
      {"MeshThatIsNotAMesh", [](const fs::path& d) { WriteText(d / "W" / "scene" / "mesh.ply", "hello, I am a text file\n"); },
       kRestore, "{D}/W/scene/mesh.ply", ""},
      {"MeshWithMoreFacesThanItsHeaderDeclares",
       [](const fs::path& d) { AppendBytes(d / "W" / "scene" / "mesh.ply", std::string(13, '\0')); },
       kRestore, "{D}/W/scene/mesh.ply", "more data than its header declares"},
      {"MeshCutShort",
       [](const fs::path& d) {
         const fs::path path = d / "W" / "scene" / "mesh.ply";
         fs::resize_file(path, fs::file_size(path) - 100);
       },
       kRestore, "{D}/W/scene/mesh.ply", ""},
      // The LUT.
      {"MissingLut", [](const fs::path& d) { fs::remove(d / "lut.lut"); }, kRestore, "{D}/lut.lut", "no such file"},
      {"LutWithANegativeAlpha",
       [](const fs::path& d) {
         FrustumLut lut = ReadLut(d / "lut.lut");
         lut.node(5).alpha[1] = -0.5;
         fs::remove(d / "lut.lut");
         WriteLut(lut, d / "lut.lut");
       },
       kRestore, "{D}/lut.lut", "negative alpha"},
      {"LutCutShort",
       [](const fs::path& d) { fs::resize_file(d / "lut.lut", fs::file_size(d / "lut.lut") / 2); }, kRestore,
       "{D}/lut.lut", ""},
      {"LutForAnotherImageSize",
       [](const fs::path& d) {
         FrustumLut lut = ReadLut(d / "lut.lut");
         FrustumLutGrid grid = lut.grid();
         grid.image_width = 640;
         grid.image_height = 480;
         FrustumLut other(grid);
         for (int n = 0; n < grid.NumNodes(); ++n) other.node(n) = lut.node(n);
         fs::remove(d / "lut.lut");
         WriteLut(other, d / "lut.lut");
       },
       kRestore, "{D}/lut.lut", "640x480"},
      {"CoverageForAnotherGrid",
       [](const fs::path& d) {
         FrustumLutGrid grid = ReadLut(d / "lut.lut").grid();
         grid.nx = 8;
         WriteLut(FrustumLut(grid), d / "coverage.lut");
       },
       kRestore, "{D}/coverage.lut", "another LUT grid"},
      // The images.
      {"MissingImage", [](const fs::path& d) { fs::remove(d / "W" / "images" / FirstImageName(d)); }, kRestore,
       "/W/images/", "no such image"},
      {"ImageOfTheWrongSize",
       [](const fs::path& d) { cv::imwrite((d / "W" / "images" / FirstImageName(d)).string(), cv::Mat(10, 20, CV_8UC3, cv::Scalar(9, 9, 9))); },
       kRestore, "/W/images/", "is 20x10 but its camera is 160x120"},
      {"ImageOfTheWrongBitDepth",
       [](const fs::path& d) { cv::imwrite((d / "W" / "images" / FirstImageName(d)).string(), cv::Mat(120, 160, CV_16UC3, cv::Scalar(9, 9, 9))); },
       kRestore, "/W/images/", "16"},
      {"ImageThatIsNotAnImage",
       [](const fs::path& d) { WriteText(d / "W" / "images" / FirstImageName(d), "GIF89a, or not"); }, kRestore,
       "/W/images/", "not an image"},
      // Targets, rigs, georeference, scene descriptions.
      {"TargetsFileThatIsNotJson", [](const fs::path& d) { WriteText(d / "targets.json", "{\"targets\": [ oops"); },
       kCalibrate, "{D}/targets.json", "not valid JSON (line 1, column 15)"},
      {"MissingTargetsFile", [](const fs::path& d) { fs::remove(d / "targets.json"); }, kCalibrate,
       "{D}/targets.json", "no such targets file"},
      {"RigFileWithAnUnknownBeamProfile",
       [](const fs::path& d) {
         WriteText(d / "rig.json", "{\"lights\": [{\"position\": [0, 0, 0], \"direction\": [0, 0, 1], \"profile\": \"laser\"}]}");
       },
       kCalibrate + " --shading-rig {D}/rig.json", "{D}/rig.json", "laser"},
      {"GeoreferenceWithAnUnknownKey",
       [](const fs::path& d) { WriteText(d / "W" / "georef.json", "{\"crs\": \"EPSG:32632\", \"origin\": [0, 0, 0], \"datum\": 1}"); },
       "mosaic" + kDive, "{D}/W/georef.json", "unknown key datum"},
      {"UnknownCrs", {}, "mosaic" + kDive + " --crs EPSG:999999 --crs-origin 0,0,0", "EPSG:999999", ""},
      {"NegativeGsd", {}, "mosaic" + kDive + " --gsd -1", "--gsd", ""},
      {"SceneDescriptionThatIsNotJson", [](const fs::path& d) { WriteText(d / "scene.json", "{\"camera\": "); },
       "simulate --scene {D}/scene.json --output {D}/simulated", "{D}/scene.json", "not valid JSON"},
      // Memory and concurrency.
      {"CameraTooLargeForTheMemoryLimit",
       [](const fs::path& d) { Edit(d / "W" / "sparse" / "0" / "cameras.txt", "PINHOLE 160 120", "PINHOLE 40000 30000"); },
       "raycast" + kDive + " --memory-limit 4096", "{D}/W", "more than the memory limit"},
      {"MemoryLimitBelowWhatTheDiveNeeds", {}, kRestore + " --memory-limit 1", "{D}/W",
       "more than the memory limit of 1 MiB"},
      // Above what the dive needs without the faces' tables (about 5 MiB with a 1 MiB fusion budget).
      {"TextureMemoryLimitBelowWhatTheFacesNeed", {}, "texture" + kDive + " --fusion-memory 1 --memory-limit 6",
       "{D}/W", "the faces' view and chart tables 1 MiB, the view selection of a region 1 MiB"},
  };
}

// Runs `lutex ARGUMENTS`; the result's output is what it wrote on stderr (stdout is dropped).
testing::CommandResult StderrOf(const std::string& arguments) {
  return testing::RunCommand("( " + std::string(LUTEX_BINARY) + " " + arguments + " 2>&1 >/dev/null )");
}

// gtest prints a case by its name.
void PrintTo(const BadInput& bad, std::ostream* out) { *out << bad.name; }

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, OneLineNamingTheFileNonZeroExitNothingWritten) {
  const BadInput& bad = GetParam();
  const fs::path& pristine = PristineDive();
  testing::TempDir scratch;
  const fs::path dive = scratch.path() / "D";
  fs::copy(pristine, dive, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
  if (bad.make) bad.make(dive);
  const std::map<fs::path, std::string> before = testing::TreeSnapshot(dive);
  const testing::CommandResult result = StderrOf(Expand(bad.command, dive));
  EXPECT_NE(result.exit_code, 0);
  std::vector<std::string> lines;
  std::istringstream text(result.output);
  for (std::string line; std::getline(text, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), 1u) << result.output;
  RecordProperty("stderr", lines[0]);  // --gtest_output=xml lists what the user sees, for the README's table
  EXPECT_NE(lines[0].find(Expand(bad.names, dive)), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(bad.says), std::string::npos) << lines[0];
  EXPECT_EQ(lines[0].find("std::"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[0].find("libpng"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[0].find("json.exception"), std::string::npos) << lines[0];
  EXPECT_TRUE(testing::TreeSnapshot(dive) == before) << "files were added, removed or changed";
}

INSTANTIATE_TEST_SUITE_P(Readme, BadInputTest, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<BadInput>& case_info) { return case_info.param.name; });

// A second writer while another lutex process holds the workspace: refused, naming the holder.
TEST(BadInput, ASecondWriterOnABusyWorkspaceIsRefused) {
  testing::TempDir scratch;
  const fs::path dive = scratch.path() / "D";
  fs::copy(PristineDive(), dive, fs::copy_options::recursive);
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t holder = fork();
  if (holder == 0) {
    ExclusiveFileLock lock(dive / "W" / "lutex" / ".lock", "W");
    const char byte = 1;
    (void)!write(ready[1], &byte, 1);
    pause();
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  const std::map<fs::path, std::string> before = testing::TreeSnapshot(dive);
  for (const std::string& command : {kRestore, "raycast" + kDive, std::string("report --workspace {D}/W")}) {
    const testing::CommandResult result = StderrOf(Expand(command, dive));
    EXPECT_EQ(result.exit_code, 1) << command;
    EXPECT_NE(result.output.find("is in use by lutex pid " + std::to_string(holder)), std::string::npos) << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  }
  EXPECT_TRUE(testing::TreeSnapshot(dive) == before);
  kill(holder, SIGKILL);
  waitpid(holder, nullptr, 0);
  // The holder is gone: its lock is taken over (with a warning) and the command runs.
  const testing::CommandResult after = testing::RunCommand(std::string(LUTEX_BINARY) + " " + Expand(kRestore, dive));
  EXPECT_EQ(after.exit_code, 0) << after.output;
  EXPECT_NE(after.output.find("taking it over"), std::string::npos) << after.output;
  EXPECT_FALSE(fs::exists(dive / "W" / "lutex" / ".lock"));
}

// A full disk: named as such, with the file being written; nothing partial is left. Needs a file system
// to fill: a 32 KiB tmpfs mounted in a private mount namespace (unshare; root), else skipped.
TEST(BadInput, AFullDiskIsNamedAsSuchAndLeavesNothingPartial) {
  testing::TempDir scratch;
  const fs::path dive = scratch.path() / "D";
  fs::copy(PristineDive(), dive, fs::copy_options::recursive);
  const fs::path small = scratch.path() / "small";
  fs::create_directories(small);
  const fs::path listing = scratch.path() / "listing.txt";
  const std::string inside = "mount -t tmpfs -o size=32k tmpfs " + small.string() + " || exit 77; " +
                             std::string(LUTEX_BINARY) + " " + Expand(kRestore, dive) + " --output " +
                             (small / "restored").string() + " >/dev/null 2>" + (scratch.path() / "stderr.txt").string() +
                             "; status=$?; find " + small.string() + " -type f > " + listing.string() + "; exit $status";
  if (!testing::HaveProgram("unshare")) GTEST_SKIP() << "no unshare here to mount a small file system";
  const testing::CommandResult result = testing::RunCommand("unshare -m sh -c '" + inside + "'");
  if (result.exit_code == 77) {
    GTEST_SKIP() << "cannot mount a small file system here (needs root and unshare): " << result.output;
  }
  EXPECT_EQ(result.exit_code, 1);
  // Work had started: its progress lines come first, then the one error line.
  std::vector<std::string> errors;
  std::istringstream lines(ReadText(scratch.path() / "stderr.txt"));
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.rfind("[lutex info]", 0) != 0) errors.push_back(line);
  }
  ASSERT_EQ(errors.size(), 1u) << ReadText(scratch.path() / "stderr.txt");
  const std::string& error = errors[0];
  EXPECT_NE(error.find("the disk is full"), std::string::npos) << error;
  EXPECT_NE(error.find((small / "restored").string()), std::string::npos) << error;
  // What was written before the disk filled was renamed into place complete; no temporary is left.
  std::istringstream files(ReadText(listing));
  for (std::string file; std::getline(files, file);) {
    EXPECT_EQ(file.find(".tmp"), std::string::npos) << file;
  }
}

}  // namespace
}  // namespace lutex
