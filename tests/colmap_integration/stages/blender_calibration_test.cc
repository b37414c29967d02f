// The method end to end on data lutex did not render (Blender Cycles, ../shared/datasets/dev): calibrate
// from the two colour boards (calib_boards_clear) and pure water (purewater_clear), restore the
// ColorChecker frames (checker_clear), and compare every patch with its true albedo. Error of a patch and
// channel = |mean restored linear albedo over the patch's inner pixels - true linear albedo| x 100. Issue
// bar: median over patches and channels <= 3, worst <= 10. Skips when the datasets are absent.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colmap_integration/stages/calibrate_workspace.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/image/image_io.h"
#include "lib/lut/lut_file.h"
#include "lib/model/water.h"
#include "tests/support/blender_dataset.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// Calibrates from a water's two colour boards and its pure water, shading with the metadata's rig
// (lutex calibrate --shading-rig) or, without `with_rig`, with the rig lutex fits (the default), into `dir`;
// starting from `reference_water` (by default, as lutex does, the named water nearest the scattering
// measured), and taking forward scattering out unless asked not to.
CalibrateSummary CalibrateFromBoards(const fs::path& dev, const std::string& water, const fs::path& dir,
                                     bool with_rig = true, const std::string& reference_water = "auto",
                                     bool remove_forward_scatter = true) {
  CalibrateOptions calibrate;
  calibrate.reference_water = reference_water;
  calibrate.remove_forward_scatter = remove_forward_scatter;
  calibrate.workspace = dev / ("calib_boards_" + water);
  if (with_rig) calibrate.calibration.grid.shading.rig = testing::LoadBlenderDataset(calibrate.workspace).rig;
  calibrate.mesh = calibrate.workspace / "scene" / "mesh.ply";
  calibrate.targets = calibrate.workspace / "metadata.json";
  calibrate.pure_water = dev / ("purewater_" + water);
  calibrate.input_encoding = ImageEncoding::kLinear16;
  calibrate.calibration.grid.z_near = 0.4;
  calibrate.calibration.grid.z_far = 3.0;
  calibrate.output = dir / "calibration" / "lut.lut";
  return CalibrateWorkspace(calibrate);
}

// The ColorChecker frames of `checker` restored with `lut` (or, without one, the raw images): the error of
// every patch and channel, sorted.
std::vector<double> SortedPatchErrors(const fs::path& checker, const fs::path& lut, const fs::path& dir) {
  fs::path images = checker / "images";
  if (!lut.empty()) {
    RestoreOptions restore;
    restore.workspace = checker;
    restore.mesh = checker / "scene" / "mesh.ply";
    restore.lut = lut;
    restore.input_encoding = ImageEncoding::kLinear16;
    restore.output = dir / "restored";
    RestoreWorkspace(restore);
    images = restore.output;
  }
  std::vector<double> errors;
  for (const auto& [id, image] : ReadSparseModel(checker / "sparse" / "0").images) {
    const std::string stem = fs::path(image.name).stem().string();
    const cv::Mat restored = ReadLinearImage(images / image.name, ImageEncoding::kLinear16);
    const cv::Mat truth = ReadLinearImage(checker / "gt" / "albedo" / (stem + ".exr"), ImageEncoding::kFloat);
    const cv::Mat regions = cv::imread((checker / "gt" / "region_id" / (stem + ".png")).string(), cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(regions.empty());
    for (int patch = 1; patch <= 24; ++patch) {
      cv::Mat inner = regions == patch;
      cv::erode(inner, inner, cv::Mat());  // inner pixels: one pixel off the patch border
      if (cv::countNonZero(inner) < 10) continue;
      const cv::Scalar restored_mean = cv::mean(restored, inner), true_mean = cv::mean(truth, inner);
      for (int c = 0; c < 3; ++c) errors.push_back(100.0 * std::abs(restored_mean[c] - true_mean[c]));
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

// Without a rig file lutex fits the rig and shades with it (calibrate_workspace.h, fit_rig): the issue's
// goals for clear water hold (median <= 2, worst <= 8; the exact rig gives 0.51 / 6.05, camera-centred
// shading 0.66 / 19.4), and the rig it found is recorded in the LUT's shading.
TEST(BlenderCalibration, WithoutARigFileTheFittedRigShadesTheColorChecker) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  testing::TempDir dir;
  const CalibrateSummary calibrated = CalibrateFromBoards(*dev, "clear", dir.path(), false);
  ASSERT_TRUE(calibrated.water_prior.has_value());
  EXPECT_GE(calibrated.water_prior->rig.lights.size(), 2u);  // the truth: two spots at +-0.4 m
  EXPECT_EQ(ReadLut(calibrated.lut).grid().shading.rig.lights.size(), calibrated.water_prior->rig.lights.size());
  const std::vector<double> errors = SortedPatchErrors(*dev / "checker_clear", calibrated.lut, dir.path());
  ASSERT_GT(errors.size(), 100u);
  std::printf("checker_clear, fitted rig: median %.2f, p90 %.2f, worst %.2f\n", errors[errors.size() / 2],
              errors[errors.size() * 9 / 10], errors.back());
  EXPECT_LE(errors[errors.size() / 2], 2.0);
  EXPECT_LE(errors.back(), 8.0);
}

// The water prior measures the water (lib/calibration/water_prior.h): its signal attenuation must lie
// where physics puts it, between a + b (1 - g) (all forward-scattered light returned to the direct path)
// and a + b (none), from the metadata's coefficients.
void ExpectPhysicalSignalAttenuation(const CalibrateSummary& calibrated, const testing::BlenderDataset& dataset) {
  ASSERT_TRUE(calibrated.water_prior.has_value());
  const Eigen::Vector3d a = dataset.water.absorption, b = dataset.water.scattering;
  const Eigen::Vector3d lowest = a + b * (1.0 - dataset.water.anisotropy_g), highest = a + b;
  const Eigen::Vector3d fitted = calibrated.water_prior->signal_attenuation;
  std::printf("%s: signal attenuation %.3f %.3f %.3f per m, physical range [%.3f %.3f %.3f] .. [%.3f %.3f %.3f]\n",
              dataset.root.filename().c_str(), fitted.x(), fitted.y(), fitted.z(), lowest.x(), lowest.y(), lowest.z(),
              highest.x(), highest.y(), highest.z());
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(fitted[c], lowest[c] - 0.01) << "channel " << c;
    EXPECT_LE(fitted[c], highest[c] + 0.01) << "channel " << c;
  }
}

TEST(BlenderCalibration, ColorCheckerPatchesFromBoardsAndPureWater) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  testing::TempDir dir;
  const CalibrateSummary calibrated = CalibrateFromBoards(*dev, "clear", dir.path());
  EXPECT_EQ(calibrated.reference_water, "clear");  // measured to scatter 0.078 per m; the water's b is 0.04 - 0.05
  ExpectPhysicalSignalAttenuation(calibrated, testing::LoadBlenderDataset(*dev / "calib_boards_clear"));
  const std::vector<double> errors = SortedPatchErrors(*dev / "checker_clear", calibrated.lut, dir.path());
  ASSERT_GT(errors.size(), 100u);
  const double median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10], worst = errors.back();
  std::printf("checker_clear: %zu patch-channels, median %.2f, p90 %.2f, worst %.2f (residual RMS %.4f %.4f %.4f)\n",
              errors.size(), median, p90, worst, calibrated.calibration.known_color_rms.x(),
              calibrated.calibration.known_color_rms.y(), calibrated.calibration.known_color_rms.z());
  EXPECT_LE(median, 3.0);  // the bars
  EXPECT_LE(worst, 10.0);
}

// In turbid water (calib_boards_turbid, purewater_turbid, checker_turbid) the pure-water frames must now
// be accepted (before, every one was rejected for its fireflies), the water measured, and the restored
// ColorChecker far better than the raw images (tools' README: raw median 17.7, worst 89.0 with an oracle
// gain per channel). The reference water is the coastal preset, whose forward scattering, lowered to what
// the boards say the water scatters, is taken out of the images (lib/model/forward_scatter.h): the
// issue's turbid goals (median <= 5, worst <= 20) hold.
TEST(BlenderCalibration, TurbidWaterIsMeasuredAndTheColorCheckerRestored) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  testing::TempDir dir;
  const CalibrateSummary calibrated = CalibrateFromBoards(*dev, "turbid", dir.path());
  // The scattering measured from the first fit (lib/calibration/forward_scatter_estimate.h; 0.32 per m
  // with this rig, 0.39 with the fitted one) lies near the water's b (0.35 - 0.42), below what its
  // attenuation leaves beyond pure water's absorption (0.45). The coastal preset is the nearest, which
  // lutex then fits from, and its b is taken out where it is smaller than the measurement.
  const testing::BlenderDataset boards = testing::LoadBlenderDataset(*dev / "calib_boards_turbid");
  ASSERT_TRUE(calibrated.measured_scattering);
  const double measured = *calibrated.measured_scattering;
  EXPECT_GE(measured, 0.8 * boards.water.scattering.minCoeff());
  EXPECT_LE(measured, (boards.water.absorption + boards.water.scattering - WaterPreset("clear")->absorption).minCoeff());
  const ForwardScatter taken_out = ReadLut(calibrated.lut).grid().forward_scatter;
  EXPECT_EQ(calibrated.reference_water, "coastal");
  EXPECT_EQ(calibrated.reference_water_reason, "nearest the measurement");
  EXPECT_EQ(taken_out, calibrated.forward_scatter);
  EXPECT_EQ(taken_out.scattering, WaterPreset("coastal")->scattering.cwiseMin(Eigen::Vector3d::Constant(measured)));
  EXPECT_EQ(calibrated.num_pure_water_skipped, 0u);
  ExpectPhysicalSignalAttenuation(calibrated, boards);
  const std::vector<double> errors = SortedPatchErrors(*dev / "checker_turbid", calibrated.lut, dir.path());
  ASSERT_GT(errors.size(), 100u);
  std::printf("checker_turbid: median %.2f, p90 %.2f, worst %.2f\n", errors[errors.size() / 2],
              errors[errors.size() * 9 / 10], errors.back());
  EXPECT_LE(errors[errors.size() / 2], 5.0);  // the turbid goals
  // Measured 33.5 before forward scattering was taken out (the white and black patches pulled towards the
  // grey surround), 12.2 after (README, 'Forward scattering'); raw is 89.
  EXPECT_LE(errors.back(), 20.0);
}

// In air (inair_whiteboard): calibrate from the white board (albedo 0.8) with one known colour, beta held
// at 0, shading towards `flash` (or, without one, towards the flash calibrate fits), restore the frames
// with the red sphere, and return the sorted errors of the sphere's pixel-channels against their true
// albedo. The calibration is returned in `calibrated`.
std::vector<double> InAirRedSphereErrors(const fs::path& dev, const std::optional<Eigen::Vector3d>& flash,
                                         const fs::path& scratch, CalibrateSummary* calibrated) {
  const testing::BlenderDataset dataset = testing::LoadBlenderDataset(dev / "inair_whiteboard");
  CalibrateOptions calibrate;
  calibrate.workspace = dataset.root;
  calibrate.mesh = dataset.root / "scene" / "mesh.ply";
  calibrate.targets = dataset.root / "metadata.json";
  calibrate.input_encoding = ImageEncoding::kLinear16;
  calibrate.calibration.in_air = true;
  if (flash) calibrate.calibration.grid.shading.light_in_cam = *flash;
  calibrate.calibration.grid.z_near = 0.4;
  calibrate.calibration.grid.z_far = 3.0;
  calibrate.output = scratch / "calibration" / "lut.lut";
  *calibrated = CalibrateWorkspace(calibrate);

  RestoreOptions restore;
  restore.workspace = dataset.root;
  restore.mesh = calibrate.mesh;
  restore.lut = calibrated->lut;
  restore.input_encoding = ImageEncoding::kLinear16;
  restore.output = scratch / "restored";
  RestoreWorkspace(restore);

  const Eigen::Vector3f sphere_albedo(0.57758f, 0.021219f, 0.021219f);  // metadata targets red_sphere
  std::vector<double> errors;
  for (const auto& [id, image] : dataset.model.images) {
    const std::string stem = fs::path(image.name).stem().string();
    const cv::Mat restored = ReadLinearImage(restore.output / image.name, ImageEncoding::kLinear16);
    const cv::Mat truth = ReadLinearImage(dataset.root / "gt" / "albedo" / (stem + ".exr"), ImageEncoding::kFloat);
    for (int row = 0; row < truth.rows; ++row) {
      for (int col = 0; col < truth.cols; ++col) {
        const cv::Vec3f t = truth.at<cv::Vec3f>(row, col);
        if (std::abs(t[0] - sphere_albedo.x()) > 0.01f || std::abs(t[1] - sphere_albedo.y()) > 0.01f) continue;
        for (int c = 0; c < 3; ++c) errors.push_back(100.0 * std::abs(restored.at<cv::Vec3f>(row, col)[c] - t[c]));
      }
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

// The flash's position given (metadata light_rig: 0.1 m right of the camera). Issue bar: 3 %.
TEST(BlenderCalibration, InAirWhiteboardRestoresTheRedSphere) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  testing::TempDir dir;
  const Eigen::Vector3d flash = testing::LoadBlenderDataset(*dev / "inair_whiteboard").rig.lights.at(0).position_in_cam;
  CalibrateSummary calibrated;
  const std::vector<double> errors = InAirRedSphereErrors(*dev, flash, dir.path(), &calibrated);
  ASSERT_GT(errors.size(), 10000u);
  std::printf("inair_whiteboard red sphere: %zu pixel-channels, median %.2f, p90 %.2f (residual RMS %.4f)\n",
              errors.size(), errors[errors.size() / 2], errors[errors.size() * 9 / 10],
              calibrated.calibration.known_color_rms.x());
  EXPECT_LE(errors[errors.size() / 2], 3.0);
}

// Without the flash's position: calibrate fits it (lib/calibration/water_prior.h) and shades with it. The
// issue's goal: within 1.25x of the error with the position given (camera-centred shading left a gradient
// of +-8 % across the board); 0.05 pp of slack, as the given position's errors are near 0.
TEST(BlenderCalibration, InAirTheFittedFlashRestoresTheRedSphereAsTheGivenOneDoes) {
  const auto dev = testing::SharedDevDatasets();
  if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
  testing::TempDir given_dir, fitted_dir;
  const Eigen::Vector3d flash = testing::LoadBlenderDataset(*dev / "inair_whiteboard").rig.lights.at(0).position_in_cam;
  CalibrateSummary given_calibration, calibrated;
  const std::vector<double> given = InAirRedSphereErrors(*dev, flash, given_dir.path(), &given_calibration);
  const std::vector<double> errors = InAirRedSphereErrors(*dev, std::nullopt, fitted_dir.path(), &calibrated);
  ASSERT_GT(errors.size(), 10000u);
  ASSERT_EQ(errors.size(), given.size());
  ASSERT_TRUE(calibrated.water_prior.has_value());
  ASSERT_EQ(calibrated.water_prior->rig.lights.size(), 1u);
  const Eigen::Vector3d fitted = calibrated.water_prior->rig.lights[0].position_in_cam;
  const auto median = [](const std::vector<double>& e) { return e[e.size() / 2]; };
  const auto p90 = [](const std::vector<double>& e) { return e[e.size() * 9 / 10]; };
  std::printf("inair_whiteboard, fitted flash at (%.3f, %.3f, %.3f) m: red sphere median %.2f, p90 %.2f "
              "(flash given: %.2f, %.2f)\n",
              fitted.x(), fitted.y(), fitted.z(), median(errors), p90(errors), median(given), p90(given));
  EXPECT_LT((fitted - flash).norm(), 0.03);
  EXPECT_LE(median(errors), 1.25 * median(given) + 0.05);
  EXPECT_LE(p90(errors), 1.25 * p90(given) + 0.05);
}

}  // namespace
}  // namespace lutex
