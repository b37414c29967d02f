// lutex mesh from the command line: a mesh from a sparse model written where it belongs, and bad models
// as one line naming the model, with nothing written.

#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_io.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// Nine images looking down at a gentle slope z = 0.1 x from 2 m, and `points` of it seen by 3 images each.
void MakeWorkspace(const fs::path& root, const std::vector<Eigen::Vector3d>& points) {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 640, 480, 400.0, 400.0);
  std::uint32_t id = 1;
  for (double y : {-1.0, 0.0, 1.0}) {
    for (double x : {-1.0, 0.0, 1.0}) {
      Image image;
      image.image_id = id;
      image.camera_id = 1;
      image.name = "img" + std::to_string(id++) + ".png";
      image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(x, y, 2.0 + 0.1 * x), Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(0, -1, 0));
      model.images[image.image_id] = image;
    }
  }
  std::uint64_t point_id = 1;
  for (const Eigen::Vector3d& xyz : points) {
    Point3D point;
    point.point3D_id = point_id;
    point.xyz = xyz;
    point.error = 0.5;
    const std::uint32_t first = 1 + static_cast<std::uint32_t>(point_id % 7);
    point.track = {{first, 0}, {first + 1, 0}, {first + 2, 0}};
    model.points3D[point_id++] = point;
  }
  WriteSparseModel(model, root / "sparse" / "0", SparseFormat::kBinary);
  fs::create_directories(root / "images");
}

std::vector<Eigen::Vector3d> Slope(int n) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -1.5 + 3.0 * i / (n - 1), y = -1.2 + 2.4 * j / (n - 1);
      points.emplace_back(x, y, 0.1 * x);
    }
  }
  return points;
}

TEST(MeshCommand, WritesTheSlopeOfTheSparsePointsIntoTheWorkspace) {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), Slope(30));
  const testing::CommandResult result =
      testing::RunCommand(std::string(LUTEX_BINARY) + " mesh --workspace " + dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("the survey is a terrain seen from above"), std::string::npos) << result.output;
  const Mesh mesh = ReadMesh(dir.path() / "lutex" / "mesh" / "mesh.ply");
  ASSERT_GT(mesh.faces.size(), 100u);
  double worst = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (std::abs(v.x()) < 1.4 && std::abs(v.y()) < 1.1) worst = std::max(worst, std::abs(v.z() - 0.1 * v.x()));
  }
  EXPECT_LT(worst, 0.005);
}

TEST(MeshCommand, ADenseWorkspacesFusedCloudIsUsedWhenPresent) {
  testing::TempDir dir;
  MakeWorkspace(dir.path(), {});  // no sparse points at all
  // W/dense/0 as image_undistorter and stereo_fusion leave it: images/, sparse/, fused.ply.
  const fs::path dense = dir.path() / "dense" / "0";
  fs::create_directories(dense / "images");
  fs::copy(dir.path() / "sparse" / "0", dense / "sparse");
  {
    const std::vector<Eigen::Vector3d> cloud = Slope(40);
    std::ofstream ply(dense / "fused.ply");
    ply << "ply\nformat ascii 1.0\nelement vertex " << cloud.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
           "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    for (const Eigen::Vector3d& p : cloud) {
      ply << p.x() << " " << p.y() << " " << p.z() + 0.002 * std::sin(50 * p.x()) << " 0 0 1 128 128 128\n";
    }
  }
  const testing::CommandResult result =
      testing::RunCommand(std::string(LUTEX_BINARY) + " mesh --workspace " + dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("points of " + (dense / "fused.ply").string()), std::string::npos) << result.output;
  const Mesh mesh = ReadMesh(dir.path() / "lutex" / "mesh" / "mesh.ply");
  double worst = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (std::abs(v.x()) < 1.4 && std::abs(v.y()) < 1.1) worst = std::max(worst, std::abs(v.z() - 0.1 * v.x()));
  }
  EXPECT_LT(worst, 0.005);
}

TEST(MeshCommand, BadModelsAreOneLineNamingTheModel) {
  struct Case {
    std::vector<Eigen::Vector3d> points;
    std::string expected;
  };
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 50; ++i) line.emplace_back(-1.0 + 0.04 * i, 0.0, 0.0);
  const std::vector<Case> cases = {{{}, "the model has no 3-D points"},
                                   {line, "lie on a line"},
                                   {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "only 3 of the model's 3 3-D points"}};
  for (const Case& c : cases) {
    testing::TempDir dir;
    MakeWorkspace(dir.path(), c.points);
    const testing::CommandResult result =
        testing::RunCommand(std::string(LUTEX_BINARY) + " mesh --workspace " + dir.path().string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    int error_lines = 0;
    std::istringstream lines(result.output);
    for (std::string text; std::getline(lines, text);) error_lines += text.find("error") != std::string::npos;
    EXPECT_EQ(error_lines, 1) << result.output;
    EXPECT_NE(result.output.find((dir.path() / "sparse" / "0").string() + ": "), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir.path() / "lutex")) << "something was written";
  }
}

}  // namespace
}  // namespace lutex
