// Self-calibration on the Blender seafloor (../shared/datasets/dev/seafloor_clear: a textured terrain of
// many colours, 36 images, lawnmower survey at 1.6-2.2 m, clear water, two spots). Two set-ups:
//   (a) known colours from the boards (calib_boards_clear) + correspondences from the survey + pure water;
//   (b) correspondences + pure water only, scale from a grey-world albedo of 0.3.
// Measured per set-up: the mean absolute error of the restored albedo against gt/albedo (percentage
// points; pixels with a surface, 2 px off depth edges, as the shared albedo_error.py), and cross-view
// consistency: for surface points seen by several images, the spread (standard deviation / mean) of
// the colour of the same point across the images, restored and unrestored. Skips without the datasets.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "colmap_integration/stages/calibrate_workspace.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/shared_datasets.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

struct Frame {
  Rigid3d cam_from_world;
  cv::Mat raw, restored, truth;
  GeometryMaps maps;
  cv::Mat interior;  // CV_8U: surface pixels 2 px away from no-surface and from depth steps
};

class BlenderSeafloor : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dev = testing::SharedDevDatasets();
    if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
    dev_ = *dev;
    survey_ = dev_ / "seafloor_clear";
  }

  CalibrateOptions Calibration(const fs::path& output) const {
    CalibrateOptions options;
    options.workspace = survey_;
    options.mesh = survey_ / "scene" / "mesh.ply";
    options.correspondences = true;
    options.pure_water = dev_ / "purewater_clear";
    options.input_encoding = ImageEncoding::kLinear16;
    options.calibration.grid.z_near = 0.4;
    options.calibration.grid.z_far = 3.0;
    options.output = output / "lut.lut";
    return options;
  }

  std::vector<Frame> Restore(const fs::path& lut, const fs::path& output) const {
    RestoreOptions restore;
    restore.workspace = survey_;
    restore.mesh = survey_ / "scene" / "mesh.ply";
    restore.lut = lut;
    restore.input_encoding = ImageEncoding::kLinear16;
    restore.output = output;
    RestoreWorkspace(restore);
    const SparseModel model = ReadSparseModel(survey_ / "sparse" / "0");
    const RaycastScene scene(ReadMesh(survey_ / "scene" / "mesh.ply"));
    const CameraRays rays(model.cameras.begin()->second);
    std::vector<Frame> frames;
    for (const auto& [id, image] : model.images) {
      Frame frame;
      frame.cam_from_world = image.cam_from_world;
      frame.raw = ReadLinearImage(survey_ / "images" / image.name, ImageEncoding::kLinear16);
      frame.restored = ReadLinearImage(output / image.name, ImageEncoding::kLinear16);
      frame.truth = ReadLinearImage(survey_ / "gt" / "albedo" / (fs::path(image.name).stem().string() + ".exr"),
                                    ImageEncoding::kFloat);
      frame.maps = scene.Render(rays, image.cam_from_world);
      cv::Mat surface = frame.maps.depth == frame.maps.depth;
      cv::Mat dx, dy;
      cv::Mat depth = frame.maps.depth.clone();
      depth.setTo(0, ~surface);
      cv::Sobel(depth, dx, CV_32F, 1, 0);
      cv::Sobel(depth, dy, CV_32F, 0, 1);
      cv::Mat step = cv::abs(dx) + cv::abs(dy) > 0.08f * depth;  // a depth edge, not a slope
      frame.interior = surface & ~step;
      cv::erode(frame.interior, frame.interior, cv::Mat::ones(5, 5, CV_8U));
      frames.push_back(std::move(frame));
    }
    return frames;
  }

  static double MeanAbsoluteError(const std::vector<Frame>& frames) {
    double sum = 0.0;
    std::size_t count = 0;
    for (const Frame& frame : frames) {
      for (int row = 0; row < frame.truth.rows; ++row) {
        for (int col = 0; col < frame.truth.cols; ++col) {
          if (!frame.interior.at<uchar>(row, col)) continue;
          for (int c = 0; c < 3; ++c) {
            sum += std::abs(frame.restored.at<cv::Vec3f>(row, col)[c] - frame.truth.at<cv::Vec3f>(row, col)[c]);
            ++count;
          }
        }
      }
    }
    return 100.0 * sum / static_cast<double>(count);
  }

  // Mean over points (every 8th interior pixel of every frame, seen by at least 3 frames) and channels of
  // std / mean of the point's colour across the frames that see it (depth test 1 %).
  static double CrossViewSpread(const std::vector<Frame>& frames, const CameraRays& rays, bool restored) {
    double sum = 0.0;
    std::size_t count = 0;
    for (const Frame& frame : frames) {
      const Rigid3d world_from_cam = frame.cam_from_world.Inverse();
      for (int row = 4; row < frame.raw.rows; row += 8) {
        for (int col = 4; col < frame.raw.cols; col += 8) {
          if (!frame.interior.at<uchar>(row, col)) continue;
          const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
          const Eigen::Vector3d point = world_from_cam * ((frame.maps.depth.at<float>(row, col) / direction.z()) * direction);
          std::vector<Eigen::Vector3d> colors;
          for (const Frame& other : frames) {
            const Eigen::Vector3d in_cam = other.cam_from_world * point;
            if (in_cam.z() <= 0) continue;
            const Eigen::Vector2d pixel = rays.camera().ImgFromCam(in_cam);
            const int c = static_cast<int>(pixel.x()), r = static_cast<int>(pixel.y());
            if (c < 0 || r < 0 || c >= other.raw.cols || r >= other.raw.rows || !other.interior.at<uchar>(r, c)) continue;
            if (std::abs(other.maps.depth.at<float>(r, c) - in_cam.z()) > 0.01 * in_cam.z()) continue;
            const cv::Vec3f value = (restored ? other.restored : other.raw).at<cv::Vec3f>(r, c);
            colors.emplace_back(value[0], value[1], value[2]);
          }
          if (colors.size() < 3) continue;
          Eigen::Vector3d mean = Eigen::Vector3d::Zero(), square = Eigen::Vector3d::Zero();
          for (const Eigen::Vector3d& color : colors) {
            mean += color / static_cast<double>(colors.size());
            square += color.cwiseAbs2() / static_cast<double>(colors.size());
          }
          for (int ch = 0; ch < 3; ++ch) {
            if (mean[ch] <= 1e-6) continue;
            sum += std::sqrt(std::max(square[ch] - mean[ch] * mean[ch], 0.0)) / mean[ch];
            ++count;
          }
        }
      }
    }
    return sum / static_cast<double>(count);
  }

  void Report(const char* setup, const CalibrateSummary& calibrated, const std::vector<Frame>& frames,
              double* mae, double* restored_spread, double* raw_spread) const {
    const SparseModel model = ReadSparseModel(survey_ / "sparse" / "0");
    const CameraRays rays(model.cameras.begin()->second);
    *mae = MeanAbsoluteError(frames);
    *restored_spread = CrossViewSpread(frames, rays, true);
    *raw_spread = CrossViewSpread(frames, rays, false);
    std::printf("%s: %zu known-colour, %zu correspondences; MAE %.2f; cross-view spread restored %.3f, raw %.3f\n",
                setup, calibrated.calibration.num_known_color, calibrated.calibration.num_correspondences, *mae,
                *restored_spread, *raw_spread);
  }

  fs::path dev_, survey_;
};

TEST_F(BlenderSeafloor, BoardsPlusCorrespondencesRestoreTheSurvey) {
  testing::TempDir dir;
  CalibrateOptions options = Calibration(dir.path() / "a");
  options.targets = dev_ / "calib_boards_clear" / "metadata.json";
  options.targets_workspace = dev_ / "calib_boards_clear";
  options.targets_mesh = options.targets_workspace / "scene" / "mesh.ply";
  const CalibrateSummary calibrated = CalibrateWorkspace(options);
  const std::vector<Frame> frames = Restore(calibrated.lut, dir.path() / "restored");
  double mae, restored_spread, raw_spread;
  Report("(a) boards + correspondences + pure water", calibrated, frames, &mae, &restored_spread, &raw_spread);
  EXPECT_GT(calibrated.calibration.num_correspondences, 10000u);
  EXPECT_LT(mae, 4.5);  // measured 1.27 (2.14 with forward scattering kept, 3.50 with the paper's weights; raw 25.1, best classical 5.5 with an oracle gain)
  EXPECT_LT(restored_spread, 0.5 * raw_spread);
}

TEST_F(BlenderSeafloor, CorrespondencesAndPureWaterAloneRestoreTheSurveyUpToScale) {
  testing::TempDir dir;
  CalibrateOptions options = Calibration(dir.path() / "b");
  options.calibration.grey_world_albedo = Eigen::Vector3d::Constant(0.3);
  const CalibrateSummary calibrated = CalibrateWorkspace(options);
  std::vector<Frame> frames = Restore(calibrated.lut, dir.path() / "restored");
  double mae, restored_spread, raw_spread;
  Report("(b) correspondences + pure water, grey world 0.3", calibrated, frames, &mae, &restored_spread, &raw_spread);
  // The scale is the grey-world assumption's; with one least-squares gain per channel (what the shared
  // albedo_error.py --scale gain does) the rest is the LUT's shape.
  Eigen::Vector3d product = Eigen::Vector3d::Zero(), square = Eigen::Vector3d::Zero();
  for (const Frame& frame : frames) {
    for (int row = 0; row < frame.truth.rows; ++row) {
      for (int col = 0; col < frame.truth.cols; ++col) {
        if (!frame.interior.at<uchar>(row, col)) continue;
        for (int c = 0; c < 3; ++c) {
          product[c] += frame.restored.at<cv::Vec3f>(row, col)[c] * frame.truth.at<cv::Vec3f>(row, col)[c];
          square[c] += std::pow(frame.restored.at<cv::Vec3f>(row, col)[c], 2);
        }
      }
    }
  }
  const Eigen::Vector3d gain = product.cwiseQuotient(square);
  for (Frame& frame : frames) frame.restored = frame.restored.mul(cv::Scalar(gain.x(), gain.y(), gain.z()));
  const double mae_after_gain = MeanAbsoluteError(frames);
  std::printf("(b) after one gain per channel (%.3f %.3f %.3f): MAE %.2f\n", gain.x(), gain.y(), gain.z(), mae_after_gain);
  EXPECT_LT(mae_after_gain, 4.5);  // measured 1.96 (2.50 with forward scattering kept, 3.22 with the paper's weights)
  EXPECT_LT(restored_spread, 0.5 * raw_spread);
}

}  // namespace
}  // namespace lutex
