// `lutex simulate` end to end on small scenes: the workspace it writes is a real COLMAP workspace whose
// ground truth agrees with what lutex computes from it, and bad descriptions fail clearly.

#include <fstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/colmap_array.h"
#include "lib/model/scene_description.h"
#include "colmap_integration/stages/simulate_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/lut/lut_file.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// A 6-image survey of a small synthetic seafloor in clear water, 160x120, noise-free 16-bit output.
const char* kSmallScene = R"({
  "mesh": {"synthetic": {"size": [4, 3], "cell_size": 0.1, "relief": 0.1, "boulders": 1, "seed": 3}},
  "camera": {"model": "OPENCV", "width": 160, "height": 120, "params": [80, 80, 80, 60, -0.05, 0.01, 0, 0]},
  "survey": {"pattern": "lawnmower", "x": [-1, 1], "y": [-0.5, 0.5], "lines": 2, "images_per_line": 3, "altitude": 1.5},
  "lights": [{"position": [-0.3, 0, 0], "power_W": 10, "profile": "cosine_power", "exponent": 2},
             {"position": [0.3, 0, 0], "power_W": 10, "profile": "cosine_power", "exponent": 2}],
  "water": {"absorption": [0.35, 0.05, 0.02], "scattering": [0.04, 0.045, 0.05], "g": 0.88},
  "sensor": {"exposure": 4.0},
  "output": {"encoding": "linear16", "sparse_format": "binary"},
  "lut": {"nx": 8, "ny": 6, "nz": 4, "z_near": 0.8, "z_far": 3.0}
})";

fs::path WriteScene(const fs::path& folder, const std::string& text) {
  const fs::path path = folder / "scene.json";
  std::ofstream(path) << text;
  return path;
}

TEST(Simulate, WritesAConsistentWorkspaceWithGroundTruth) {
  testing::TempDir dir;
  SimulateOptions options;
  options.scene = WriteScene(dir.path(), kSmallScene);
  options.output = dir.path() / "W";
  const SimulateSummary summary = SimulateWorkspace(options);
  ASSERT_EQ(summary.num_images, 6u);

  const SparseModel model = ReadSparseModel(options.output / "sparse" / "0");
  ASSERT_EQ(model.images.size(), 6u);
  EXPECT_EQ(model.cameras.at(1).model_id, CameraModelId::kOpenCV);
  const Mesh mesh = ReadMesh(options.output / "scene" / "mesh.ply");
  EXPECT_EQ(mesh.NumFaces(), summary.num_faces);
  EXPECT_FALSE(mesh.vertex_colors.empty());

  // The ground-truth depth is what lutex's ray caster sees in the written mesh with the written poses.
  const RaycastScene scene(mesh);
  const CameraRays rays(model.cameras.at(1));
  for (const auto& [id, image] : model.images) {
    const cv::Mat truth = ReadColmapArray(options.output / "ground_truth" / "depth" / (image.name + ".bin"));
    const cv::Mat depth = ReplaceNanWithZero(scene.Render(rays, image.cam_from_world).depth);
    EXPECT_LT(cv::norm(truth, depth, cv::NORM_INF), 1e-5) << image.name;
    const cv::Mat picture = ReadLinearImage(options.output / "images" / image.name, ImageEncoding::kLinear16);
    EXPECT_EQ(picture.cols, 160);
    // Water eats red: the mean red is below the mean blue although the palette is balanced.
    const cv::Scalar mean = cv::mean(picture);
    EXPECT_LT(mean[0], mean[2]) << image.name;
    const cv::Mat albedo = ReadLinearImage(options.output / "ground_truth" / "albedo" / image.name, ImageEncoding::kLinear16);
    double lowest, highest;
    cv::minMaxIdx(albedo.reshape(1), &lowest, &highest);
    EXPECT_GE(lowest, 0.0);
    EXPECT_LE(highest, 1.0);
  }
  const FrustumLut lut = ReadLut(options.output / "ground_truth" / "true.lut");
  EXPECT_EQ(lut.grid().nx, 8);
  EXPECT_EQ(lut.grid().image_width, 160);
  EXPECT_TRUE(fs::exists(options.output / "ground_truth" / "true_lut_slabs" / "slab_03_beta.png"));
}

TEST(Simulate, ImagesDoNotDependOnTheThreadCount) {
  testing::TempDir dir;
  SimulateOptions options;
  options.scene = WriteScene(dir.path(), kSmallScene);
  options.num_threads = 1;
  options.output = dir.path() / "one";
  SimulateWorkspace(options);
  options.num_threads = 2;
  options.output = dir.path() / "two";
  SimulateWorkspace(options);
  const auto read = [](const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
  };
  EXPECT_EQ(read(dir.path() / "one" / "images" / "frame_0004.png"), read(dir.path() / "two" / "images" / "frame_0004.png"));
}

std::string DescriptionError(const std::string& text) {
  testing::TempDir dir;
  try {
    ReadSceneDescription(WriteScene(dir.path(), text));
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(Simulate, BadDescriptionsNameTheProblem) {
  EXPECT_NE(DescriptionError("{not json").find("scene.json"), std::string::npos);
  EXPECT_NE(DescriptionError(R"({"camera": {"model": "PINHOLE", "width": 10, "height": 10, "params": [5, 5, 5, 5]},
                                 "lights": [{"profile": "laser"}]})").find("lights[0].profile"), std::string::npos);
  EXPECT_NE(DescriptionError(R"({"camera": {"model": "PINHOLE", "width": 10, "height": 10, "params": [5, 5, 5, 5]},
                                 "lights": [{}], "watr": "air"})").find("unknown key scene.watr"), std::string::npos);
  EXPECT_NE(DescriptionError(R"({"camera": {"model": "PINHOLE", "width": 10, "height": 10, "params": [5, 5]},
                                 "lights": [{}]})").find("takes 4 parameters"), std::string::npos);
  EXPECT_NE(DescriptionError(R"({"camera": {"model": "PINHOLE", "width": 10, "height": 10, "params": [5, 5, 5, 5]}})")
                .find("at least one light"), std::string::npos);
}

// Found reviewing the reader for fuzz/scene_fuzzer: counts and sizes read as numbers were cast to int unchecked
// (undefined behaviour for 1e30), a survey of 2^31 x 2^31 images was generated, "mesh": {} read a key it lacks.
TEST(Simulate, CountsOutOfRangeAndAnEmptyMeshAreClearErrors) {
  const std::string camera = R"("camera": {"model": "PINHOLE", "width": 10, "height": 10, "params": [5, 5, 5, 5]}, )";
  const std::string lights = R"("lights": [{}])";
  EXPECT_NE(DescriptionError("{" + camera + lights + R"(, "lut": {"nx": 1e30}})")
                .find("lut.nx must be a whole number from 1 to 4096"), std::string::npos);
  EXPECT_NE(DescriptionError(R"({"camera": {"model": "PINHOLE", "width": -1, "height": 10, "params": [5, 5, 5, 5]}, )" +
                             lights + "}")
                .find("camera.width must be a whole number"), std::string::npos);
  EXPECT_NE(DescriptionError("{" + camera + lights + R"(, "survey": {"lines": 100000, "images_per_line": 100000}})")
                .find("survey.lines x survey.images_per_line must be at most 100000"), std::string::npos);
  EXPECT_NE(DescriptionError("{" + camera + lights + R"(, "sensor": {"seed": 2.5}})")
                .find("sensor.seed must be a whole number"), std::string::npos);
  EXPECT_NE(DescriptionError("{" + camera + lights + R"(, "mesh": {}})").find("mesh must be a file name"),
            std::string::npos);
}

TEST(Simulate, CommandLineFailsCleanlyOnAMissingScene) {
  testing::TempDir dir;
  const testing::CommandResult result = testing::RunCommand(std::string(LUTEX_BINARY) + " simulate --scene " +
                                                            (dir.path() / "nope.json").string() + " --output " +
                                                            (dir.path() / "W").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("nope.json: no such scene description"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "W"));
}

}  // namespace
}  // namespace lutex
