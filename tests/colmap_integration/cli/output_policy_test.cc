// Inputs are sacred (colmap_integration/stages/output_policy.h): every command refuses an output that is,
// lies inside or contains one of its inputs, with one line naming both, a non-zero exit and not one byte
// changed or added anywhere in the tree.

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geometry/mesh_primitives.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/tree_snapshot.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// W: two images (their bytes are never read: the refusal comes first), a model, a mesh, a targets file,
// a LUT; everything a user could point an output at by mistake.
void MakeWorkspace(const fs::path& root) {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 64, 48, 40.0, 40.0);
  for (std::uint32_t id = 1; id <= 2; ++id) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "frame_" + std::to_string(id) + ".png";
    image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.3 * id, 0, 2.0), Eigen::Vector3d(0, 0, -1),
                                                 Eigen::Vector3d(0, -1, 0));
    model.images[id] = image;
    fs::create_directories(root / "images");
    std::ofstream(root / "images" / image.name) << "image bytes " << id;
  }
  WriteSparseModel(model, root / "sparse" / "0", SparseFormat::kBinary);
  fs::create_directories(root / "scene");
  WriteMesh(MakeHeightFieldMesh([](double, double) { return 0.0; }, -20, 20, -20, 20, 2, 2), root / "scene" / "mesh.ply");
  std::ofstream(root / "targets.json") << "{\"targets\": []}";
  std::ofstream(root / "calibration.lut") << "a LUT";
  fs::create_symlink(root / "images", root / "link_to_images");
}

struct Case {
  std::string name;
  std::string command;   // after "lutex", with W for the workspace
  std::string output;    // the offending output as given, with W
  std::string input;     // the input it would destroy, with W
  std::string relation;  // "is", "lies inside" or "contains"
};

std::string WithWorkspace(std::string text, const fs::path& workspace) {
  for (std::size_t at = text.find('W'); at != std::string::npos; at = text.find('W', at)) {
    const bool word_start = at == 0 || text[at - 1] == ' ' || text[at - 1] == '=';
    const bool word_end = at + 1 == text.size() || text[at + 1] == '/' || text[at + 1] == ' ';
    if (word_start && word_end) {
      text.replace(at, 1, workspace.string());
      at += workspace.string().size();
    } else {
      ++at;
    }
  }
  return text;
}

TEST(OutputPolicy, EveryCommandRefusesAnOutputOverOrInsideItsInputsAndChangesNothing) {
  const std::string dive = " --workspace W --mesh W/scene/mesh.ply";
  const std::vector<Case> cases = {
      {"restore into the images", "restore" + dive + " --lut W/calibration.lut --output W/images", "W/images",
       "W/images", "is"},
      {"restore into a folder inside the images", "restore" + dive + " --lut W/calibration.lut --output W/images/restored",
       "W/images/restored", "W/images", "lies inside"},
      {"restore into the workspace root, which holds the images", "restore" + dive + " --lut W/calibration.lut --output W",
       "W", "W/images", "contains"},
      {"restore through a link to the images", "restore" + dive + " --lut W/calibration.lut --output W/link_to_images/out",
       "W/link_to_images/out", "W/images", "lies inside"},
      {"calibrate over the targets file", "calibrate" + dive + " --targets W/targets.json --output W/targets.json",
       "W/targets.json", "W/targets.json", "is"},
      {"calibrate over an input image", "calibrate" + dive + " --targets W/targets.json --output W/images/frame_1.png",
       "W/images/frame_1.png", "W/images", "lies inside"},
      {"calibrate into the sparse model", "calibrate" + dive + " --targets W/targets.json --output W/sparse/0/lut.lut",
       "W/sparse/0/lut.lut", "W/sparse/0", "lies inside"},
      {"texture over the mesh", "texture" + dive + " --output W/scene/mesh.ply", "W/scene/mesh.ply", "W/scene/mesh.ply",
       "is"},
      {"mosaic into the images", "mosaic" + dive + " --output W/images/ortho.tif", "W/images/ortho.tif", "W/images",
       "lies inside"},
      {"mosaic's DEM into the sparse model", "mosaic" + dive + " --dem W/sparse/0/dem.tif", "W/sparse/0/dem.tif",
       "W/sparse/0", "lies inside"},
      {"raycast into the sparse model", "raycast" + dive + " --output W/sparse/0", "W/sparse/0", "W/sparse/0", "is"},
      {"report into the images", "report --workspace W --output W/images/report", "W/images/report", "W/images",
       "lies inside"},
  };
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "W";
  MakeWorkspace(workspace);
  const std::map<fs::path, std::string> before = testing::TreeSnapshot(dir.path());
  for (const Case& c : cases) {
    const testing::CommandResult result =
        testing::RunCommand(std::string(LUTEX_BINARY) + " " + WithWorkspace(c.command, workspace));
    EXPECT_EQ(result.exit_code, 1) << c.name << ": " << result.output;
    const std::string expected = WithWorkspace(c.output, workspace) + ": the output " + c.relation + " ";
    EXPECT_NE(result.output.find(expected), std::string::npos) << c.name << ": " << result.output;
    EXPECT_NE(result.output.find("(" + WithWorkspace(c.input, workspace) + ")"), std::string::npos)
        << c.name << ": " << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << c.name << ": " << result.output;
    EXPECT_EQ(testing::TreeSnapshot(dir.path()), before) << c.name << ": a file was written or changed";
    EXPECT_FALSE(fs::exists(workspace / "lutex")) << c.name;
  }
}

TEST(OutputPolicy, RunRefusesAMeshItWouldOverwriteBeforeAnyStageStarts) {
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "W";
  MakeWorkspace(workspace);
  // A mesh kept where lutex run writes its textured model.
  fs::create_directories(workspace / "lutex");
  fs::copy_file(workspace / "scene" / "mesh.ply", workspace / "lutex" / "model.glb");
  const std::map<fs::path, std::string> before = testing::TreeSnapshot(dir.path());
  const testing::CommandResult result = testing::RunCommand(
      std::string(LUTEX_BINARY) + " run --workspace " + workspace.string() + " --mesh " +
      (workspace / "lutex" / "model.glb").string() + " --lut " + (workspace / "calibration.lut").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find((workspace / "lutex" / "model.glb").string() + ": the output is the mesh"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(testing::TreeSnapshot(dir.path()), before);
  EXPECT_FALSE(fs::exists(workspace / "lutex" / "run"));
}

TEST(OutputPolicy, OutputsBesideTheInputsAreFine) {
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "W";
  MakeWorkspace(workspace);
  // W/images_restored shares a prefix with W/images but is not inside it.
  const testing::CommandResult result = testing::RunCommand(
      std::string(LUTEX_BINARY) + " raycast --workspace " + workspace.string() + " --mesh " +
      (workspace / "scene" / "mesh.ply").string() + " --output " + (workspace / "images_raycast").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(fs::exists(workspace / "images_raycast" / "depth_maps" / "frame_1.png.geometric.bin"));
}

// An output whose path runs through a file is refused before anything is read, naming the file in its
// way (it was a raw "filesystem error: cannot create directories: Not a directory [afile/x]" after the
// images had been read).
TEST(OutputPolicy, AnOutputThroughAFileIsRefusedNamingTheFile) {
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "W";
  MakeWorkspace(workspace);
  std::ofstream(dir.path() / "afile") << "not a folder";
  const std::map<fs::path, std::string> before = testing::TreeSnapshot(dir.path());
  for (const std::string output : {"afile/x", "afile/x/y.lut"}) {
    const testing::CommandResult result = testing::RunCommand(
        std::string(LUTEX_BINARY) + " raycast --workspace " + workspace.string() + " --mesh " +
        (workspace / "scene" / "mesh.ply").string() + " --output " + (dir.path() / output).string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find((dir.path() / output).string() + ": cannot be written, " +
                                 (dir.path() / "afile").string() + " is a file, not a folder"),
              std::string::npos)
        << result.output;
    EXPECT_EQ(result.output.find("filesystem error"), std::string::npos) << result.output;
  }
  EXPECT_EQ(testing::TreeSnapshot(dir.path()), before);
}

// A killed command leaves temporaries (".NAME.tmpPID_N.EXT"); the next command writing there removes them,
// whichever it is, and keeps those of a writer still alive (here: this test process).
TEST(OutputPolicy, ASingleCommandRemovesWhatAKilledOneLeftInItsOutput) {
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "W";
  MakeWorkspace(workspace);
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);  // now no process has this id
  const fs::path output = workspace / "raycast";
  fs::create_directories(output / "depth_maps");
  const fs::path stale = output / "depth_maps" / (".frame_1.png.geometric.tmp" + std::to_string(child) + "_0.bin");
  const fs::path live = output / "depth_maps" / (".frame_2.png.geometric.tmp" + std::to_string(getpid()) + "_0.bin");
  std::ofstream(stale) << "half a depth map";
  std::ofstream(live) << "being written";
  const testing::CommandResult result = testing::RunCommand(
      std::string(LUTEX_BINARY) + " raycast --workspace " + workspace.string() + " --mesh " +
      (workspace / "scene" / "mesh.ply").string() + " --output " + output.string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_NE(result.output.find("removed 1 unfinished file(s) of an interrupted command at " + output.string()),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace lutex
