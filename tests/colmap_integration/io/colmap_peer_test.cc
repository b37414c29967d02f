// The real COLMAP 3.8 binary as a peer: it must read what lutex writes, lutex must read what it writes,
// and both must agree on what every camera model means. Skipped when `colmap` is not installed.

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/io/colmap_array.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/io/workspace.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/point_cloud_ply.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_cameras.h"
#include "tests/support/test_models.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// COLMAP 3.8 knows model ids 0-10 (RAD_TAN_THIN_PRISM_FISHEYE came later).
constexpr int kColmap38Models = 11;

#define SKIP_WITHOUT_COLMAP()                                                        \
  if (!testing::HaveProgram("colmap")) GTEST_SKIP() << "colmap is not installed"

std::string Colmap(const std::string& arguments) {
  return "QT_QPA_PLATFORM=offscreen colmap " + arguments;
}

void RunColmap(const std::string& arguments) {
  const testing::CommandResult result = testing::RunCommand(Colmap(arguments));
  ASSERT_EQ(result.exit_code, 0) << "colmap " << arguments << "\n" << result.output;
}

// lutex binary -> colmap text -> lutex, and lutex text -> colmap binary -> lutex. COLMAP renormalises
// quaternions on reading and prints 17 significant digits, so agreement is to 1e-15, not bit-exact.
TEST(ColmapPeer, ModelConverterReadsWhatLutexWritesAndViceVersa) {
  SKIP_WITHOUT_COLMAP();
  const SparseModel model = testing::MakeTestModel(kColmap38Models);
  testing::TempDir dir;
  WriteSparseModel(model, dir.path() / "lutex_bin", SparseFormat::kBinary);
  fs::create_directories(dir.path() / "colmap_txt");
  RunColmap("model_converter --input_path " + (dir.path() / "lutex_bin").string() + " --output_path " +
            (dir.path() / "colmap_txt").string() + " --output_type TXT");
  ASSERT_EQ(DetectSparseFormat(dir.path() / "colmap_txt"), SparseFormat::kText);
  testing::ExpectModelsEqual(model, ReadSparseModel(dir.path() / "colmap_txt"), 1e-15);

  WriteSparseModel(model, dir.path() / "lutex_txt", SparseFormat::kText);
  fs::create_directories(dir.path() / "colmap_bin");
  RunColmap("model_converter --input_path " + (dir.path() / "lutex_txt").string() + " --output_path " +
            (dir.path() / "colmap_bin").string() + " --output_type BIN");
  ASSERT_EQ(DetectSparseFormat(dir.path() / "colmap_bin"), SparseFormat::kBinary);
  testing::ExpectModelsEqual(model, ReadSparseModel(dir.path() / "colmap_bin"), 1e-15);
}

// A colour that is a smooth function of the viewing ray: undistortion must move it, not change it.
cv::Vec3b RayColour(const Eigen::Vector3d& ray) {
  const double a = ray.x() / ray.z(), b = ray.y() / ray.z();
  return cv::Vec3b(cv::saturate_cast<uchar>(128 + 60 * std::sin(3 * (a + b))),
                   cv::saturate_cast<uchar>(128 + 90 * std::cos(5 * b)),
                   cv::saturate_cast<uchar>(128 + 90 * std::sin(4 * a)));
}

// A 160x120 version of the test camera of each distorted model COLMAP 3.8 knows.
std::vector<Camera> DistortedCameras() {
  std::vector<Camera> cameras;
  std::uint32_t camera_id = 1;
  for (CameraModelId model : {CameraModelId::kSimpleRadial, CameraModelId::kRadial, CameraModelId::kOpenCV,
                              CameraModelId::kOpenCVFisheye, CameraModelId::kFullOpenCV, CameraModelId::kFOV,
                              CameraModelId::kSimpleRadialFisheye, CameraModelId::kRadialFisheye,
                              CameraModelId::kThinPrismFisheye}) {
    Camera camera = testing::MakeCamera(model, camera_id++);
    const int focal_and_centre = model == CameraModelId::kSimpleRadial || model == CameraModelId::kRadial ||
                                         model == CameraModelId::kSimpleRadialFisheye ||
                                         model == CameraModelId::kRadialFisheye
                                     ? 3
                                     : 4;
    for (int k = 0; k < focal_and_centre; ++k) camera.params[k] *= 0.25;
    camera.width = 160;
    camera.height = 120;
    cameras.push_back(camera);
  }
  return cameras;
}

// Renders the ray colour into one image per distorted camera, lets `colmap image_undistorter` resample
// them to pinhole cameras, and checks that every undistorted pixel has the colour of its own ray. This
// holds only if lutex and COLMAP agree on each model's distortion and on the pixel-centre convention.
// Then lutex ray-casts a tilted plane into the undistorted images, writes depth and normal maps into
// the dense workspace, and `colmap stereo_fusion` must fuse them into points on that plane.
TEST(ColmapPeer, UndistorterAndStereoFusionAgreeWithLutex) {
  SKIP_WITHOUT_COLMAP();
  testing::TempDir dir;
  const fs::path workspace = dir.path() / "workspace";
  fs::create_directories(workspace / "images");
  SparseModel model;
  const std::vector<Camera> cameras = DistortedCameras();
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Camera& camera = cameras[i];
    model.cameras[camera.camera_id] = camera;
    Image image;
    image.image_id = camera.camera_id;
    image.camera_id = camera.camera_id;
    image.name = "img_" + std::to_string(i) + ".png";
    image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.15 * static_cast<double>(i), 0.1, 2.0),
                                                 Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
    model.images[image.image_id] = image;
    cv::Mat picture(120, 160, CV_8UC3);
    for (int row = 0; row < 120; ++row) {
      for (int col = 0; col < 160; ++col) {
        picture.at<cv::Vec3b>(row, col) = RayColour(camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5)));
      }
    }
    ASSERT_TRUE(cv::imwrite((workspace / "images" / image.name).string(), picture));
  }
  WriteSparseModel(model, workspace / "sparse" / "0", SparseFormat::kBinary);
  fs::create_directories(workspace / "dense" / "0");
  RunColmap("image_undistorter --image_path " + (workspace / "images").string() + " --input_path " +
            (workspace / "sparse" / "0").string() + " --output_path " + (workspace / "dense" / "0").string() +
            " --output_type COLMAP");

  const Workspace found = FindWorkspace(workspace);
  ASSERT_EQ(found.dense.size(), 1u);
  const DenseWorkspace& dense = found.dense[0];
  const SparseModel undistorted = ReadSparseModel(dense.sparse_dir);
  ASSERT_EQ(undistorted.images.size(), cameras.size());

  for (const auto& [image_id, image] : undistorted.images) {
    const Camera& pinhole = undistorted.cameras.at(image.camera_id);
    ASSERT_EQ(pinhole.model_id, CameraModelId::kPinhole);
    const Camera& original = model.cameras.at(image_id);
    const cv::Mat picture = cv::imread((dense.images_dir / image.name).string());
    ASSERT_FALSE(picture.empty()) << image.name;
    ASSERT_EQ(picture.cols, static_cast<int>(pinhole.width));
    double error_sum = 0.0, worst = 0.0;
    int count = 0;
    for (int row = 3; row + 3 < picture.rows; ++row) {
      for (int col = 3; col + 3 < picture.cols; ++col) {
        const Eigen::Vector3d ray = pinhole.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5));
        const Eigen::Vector2d source = original.ImgFromCam(ray);
        if (!(source.x() > 3 && source.x() < 157 && source.y() > 3 && source.y() < 117)) continue;
        const cv::Vec3b expected = RayColour(ray), actual = picture.at<cv::Vec3b>(row, col);
        for (int c = 0; c < 3; ++c) {
          const double error = std::abs(double(expected[c]) - double(actual[c]));
          error_sum += error;
          worst = std::max(worst, error);
          ++count;
        }
      }
    }
    ASSERT_GT(count, 3000) << CameraModelName(original.model_id);
    // Bilinear resampling of a smooth pattern plus 8-bit rounding: well under one level on average. A
    // half-pixel convention error or a wrong distortion term gives several levels.
    EXPECT_LT(error_sum / count, 0.8) << CameraModelName(original.model_id);
    EXPECT_LT(worst, 6.0) << CameraModelName(original.model_id);
  }

  // lutex depth and normal maps of the plane z = 0.2 x, fused by COLMAP. COLMAP finds overlapping images
  // through shared 3-D points, which this model lacks, so each fused point comes from one depth map
  // (min_num_pixels 1): what is tested is that COLMAP reads lutex's maps as the planar depth they are.
  const Mesh plane = MakeHeightFieldMesh([](double x, double) { return 0.2 * x; }, -10, 10, -10, 10, 4, 4);
  const RaycastScene scene(plane);
  double deepest = 0.0;
  for (const auto& [image_id, image] : undistorted.images) {
    const GeometryMaps maps = scene.Render(CameraRays(undistorted.cameras.at(image.camera_id)), image.cam_from_world);
    double image_deepest = 0.0;
    cv::minMaxIdx(ReplaceNanWithZero(maps.depth), nullptr, &image_deepest);
    deepest = std::max(deepest, image_deepest);
    WriteColmapArray(ReplaceNanWithZero(maps.depth), dense.DepthMapPath(image.name, "geometric"));
    WriteColmapArray(ReplaceNanWithZero(maps.normal), dense.NormalMapPath(image.name, "geometric"));
    ASSERT_EQ(cv::norm(ReadColmapArray(dense.DepthMapPath(image.name, "geometric")),
                       ReplaceNanWithZero(maps.depth), cv::NORM_INF), 0.0);
  }
  RunColmap("stereo_fusion --workspace_path " + dense.root.string() +
            " --workspace_format COLMAP --input_type geometric --StereoFusion.min_num_pixels 1 --output_path " +
            (dense.root / "fused.ply").string());
  const std::vector<Eigen::Vector3d> points = testing::ReadPlyPointPositions(dense.root / "fused.ply");
  ASSERT_GT(points.size(), 1000u);
  // COLMAP's fusion back-projects depth map pixel (col, row) through (col, row), not through the pixel
  // centre (col + 0.5, row + 0.5) where lutex measured the depth: a point moves by 0.5 z / fx along camera
  // x (= world x here), i.e. by 0.2 * 0.5 z / fx in height on this plane.
  double smallest_focal = 1e9;
  for (const auto& entry : undistorted.cameras) smallest_focal = std::min(smallest_focal, entry.second.FocalLengthX());
  const double half_pixel_bound = 0.2 * 0.5 * deepest / smallest_focal + 1e-5;
  double worst_offset = 0.0;
  for (const auto& point : points) worst_offset = std::max(worst_offset, std::abs(point.z() - 0.2 * point.x()));
  EXPECT_LT(worst_offset, half_pixel_bound) << "fused points off the plane";
  EXPECT_EQ(FindDenseWorkspace(dense.root).fused_ply, dense.root / "fused.ply");
}

}  // namespace
}  // namespace lutex
