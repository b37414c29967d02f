// `lutex restore` end to end on a simulated workspace: with the simulator's true LUT the restored images
// match the true albedo; bad inputs fail before anything is written.

#include <algorithm>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/stages/simulate_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/calibration/exposure_record.h"
#include "lib/image/image_io.h"
#include "lib/lut/lut_file.h"
#include "tests/support/exif_jpeg.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// 8 noise-free 16-bit images, one Gaussian light at the camera, clear water (the model is exact then, so
// what remains is the LUT's interpolation).
const char* kScene = R"({
  "mesh": {"synthetic": {"size": [5, 4], "cell_size": 0.05, "relief": 0.1, "boulders": 0, "seed": 4}},
  "camera": {"model": "PINHOLE", "width": 200, "height": 150, "params": [100, 100, 100, 75]},
  "survey": {"pattern": "lawnmower", "x": [-1, 1], "y": [-0.5, 0.5], "lines": 2, "images_per_line": 4, "altitude": 1.8},
  "lights": [{"position": [0, 0, 0], "intensity": [2, 2, 2], "profile": "gaussian", "sigma_deg": 45}],
  "water": {"absorption": [0.35, 0.05, 0.02], "scattering": [0.04, 0.045, 0.05], "g": 0.88},
  "sensor": {"exposure": 3.0},
  "output": {"encoding": "linear16"},
  "lut": {"nx": 20, "ny": 15, "nz": 10, "z_near": 0.8, "z_far": 3.0}
})";

// The same with every frame's exposure varied by up to 10 % (a strobe's power).
std::string SceneWithExposureVariation() {
  std::string scene = kScene;
  const std::string key = R"("sensor": {"exposure": 3.0)";
  scene.replace(scene.find(key), key.size(), key + R"(, "exposure_variation": 0.1)");
  return scene;
}

fs::path Simulated(const fs::path& folder, const std::string& scene = kScene) {
  std::ofstream(folder / "scene.json") << scene;
  SimulateOptions options;
  options.scene = folder / "scene.json";
  options.output = folder / "W";
  SimulateWorkspace(options);
  return options.output;
}

RestoreOptions OptionsFor(const fs::path& workspace) {
  RestoreOptions options;
  options.workspace = workspace;
  options.mesh = workspace / "scene" / "mesh.ply";
  options.lut = workspace / "ground_truth" / "true.lut";
  options.input_encoding = ImageEncoding::kLinear16;
  options.restoration.shot_noise = 0.0;
  options.restoration.read_noise = 1.0 / 65535;  // 16-bit quantisation only
  return options;
}

// The median |restored - true albedo| over the pixel-channels restoration is confident of (most of them).
double MedianConfidentError(const fs::path& workspace, const RestoreSummary& summary) {
  std::vector<double> errors;
  for (const auto& [id, image] : ReadSparseModel(workspace / "sparse" / "0").images) {
    const fs::path name = fs::path(image.name).replace_extension(".png");
    const cv::Mat restored = ReadLinearImage(summary.output / name, ImageEncoding::kLinear16);
    const cv::Mat truth = ReadLinearImage(workspace / "ground_truth" / "albedo" / name, ImageEncoding::kLinear16);
    const cv::Mat confidence = cv::imread((summary.confidence_output / name).string());
    EXPECT_FALSE(confidence.empty()) << image.name;
    if (confidence.empty()) return 1.0;
    for (int row = 0; row < restored.rows; ++row) {
      for (int col = 0; col < restored.cols; ++col) {
        for (int c = 0; c < 3; ++c) {
          if (confidence.at<cv::Vec3b>(row, col)[2 - c] < 128) continue;
          errors.push_back(std::abs(restored.at<cv::Vec3f>(row, col)[c] - truth.at<cv::Vec3f>(row, col)[c]));
        }
      }
    }
  }
  EXPECT_GT(errors.size(), 8u * 200 * 150);  // most pixel-channels are confident
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

// Median error over confident pixels below 1 % of full scale (measured 0.06 %).
TEST(Restore, TrueLutRestoresTheSimulatedWorkspace) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  const RestoreSummary summary = RestoreWorkspace(OptionsFor(workspace));
  ASSERT_EQ(summary.num_images, 8u);
  const double median = MedianConfidentError(workspace, summary);
  std::printf("restore with the true LUT: median error %.4f\n", median);
  EXPECT_LT(median, 0.01);
}

// Frames whose exposure varies by up to 10 %: the true LUT alone restores them several times worse; with
// exposure.json beside it holding each frame's gain (as calibration writes the fitted ones), as well as
// frames of one exposure (measured 0.0006 with, 0.038 without).
TEST(Restore, TheExposureRecordBesideTheLutDividesEachImageByItsGain) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path(), SceneWithExposureVariation());
  RestoreOptions options = OptionsFor(workspace);
  options.output = dir.path() / "without";
  const double without = MedianConfidentError(workspace, RestoreWorkspace(options));

  ExposureRecord record;
  const nlohmann::json factors = nlohmann::json::parse(std::ifstream(workspace / "ground_truth" / "exposure_factors.json"));
  for (const auto& [name, factor] : factors.items()) record.fitted_gains[name] = factor.get<double>();
  record.fitted_images = workspace / "images";
  fs::create_directories(dir.path() / "calibration");
  fs::copy_file(options.lut, dir.path() / "calibration" / "lut.lut");
  WriteExposureRecord(record, dir.path() / "calibration" / "exposure.json");
  options.lut = dir.path() / "calibration" / "lut.lut";
  options.output = dir.path() / "with";
  const RestoreSummary summary = RestoreWorkspace(options);
  EXPECT_EQ(summary.num_exposure_adjusted, 8u);
  const double with = MedianConfidentError(workspace, summary);
  std::printf("varying exposure: median error %.4f with the gains, %.4f without\n", with, without);
  EXPECT_LT(with, 0.01);
  EXPECT_GT(without, 4 * with);

  // Gains fitted for another dive's images of the same names are not applied.
  record.fitted_images = dir.path();
  WriteExposureRecord(record, dir.path() / "calibration" / "exposure.json");
  options.output = dir.path() / "other_dive";
  EXPECT_EQ(RestoreWorkspace(options).num_exposure_adjusted, 0u);
}

// The same frames as a camera's JPEGs whose EXIF says how each was exposed (ISO in proportion to its
// exposure): a record with an EXIF reference and no fitted gains restores them by EXIF alone; an image
// without the tags is restored at the reference and named in the summary (measured: median error 0.011
// with the record, 0.040 without; 8-bit JPEG with chroma subsampling).
TEST(Restore, ExifExposureRelativeToTheLutsReferenceIsDividedOut) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path(), SceneWithExposureVariation());
  const nlohmann::json factors = nlohmann::json::parse(std::ifstream(workspace / "ground_truth" / "exposure_factors.json"));
  SparseModel model = ReadSparseModel(workspace / "sparse" / "0");
  for (auto& [id, image] : model.images) {
    const cv::Mat linear = ReadLinearImage(workspace / "images" / image.name, ImageEncoding::kLinear16);
    const fs::path jpeg = fs::path(image.name).replace_extension(".jpg");
    WriteLinearImage(linear, dir.path() / "srgb.png", ImageEncoding::kSrgb8);
    const double iso = id == 1 ? 0.0 : std::round(1000 * factors[image.name].get<double>());
    testing::WriteExifJpeg(cv::imread((dir.path() / "srgb.png").string()), workspace / "images" / jpeg, 0.004, iso, 4.0);
    image.name = jpeg.string();
  }
  WriteSparseModel(model, workspace / "sparse" / "0", SparseFormat::kText);
  ExposureRecord record;
  record.exif_factors = {true, true, true};
  record.exif_reference = 0.004 * 1000 / 16;
  fs::create_directories(dir.path() / "calibration");
  fs::copy_file(workspace / "ground_truth" / "true.lut", dir.path() / "calibration" / "lut.lut");
  WriteExposureRecord(record, dir.path() / "calibration" / "exposure.json");
  RestoreOptions options = OptionsFor(workspace);
  options.input_encoding = ImageEncoding::kSrgb8;
  options.output_encoding = "linear16";
  options.restoration.read_noise = 0.002;
  options.lut = dir.path() / "calibration" / "lut.lut";
  const RestoreSummary summary = RestoreWorkspace(options);
  EXPECT_EQ(summary.num_exposure_adjusted, 7u);
  ASSERT_EQ(summary.missing_exif.size(), 1u);
  EXPECT_EQ(summary.missing_exif[0], model.images.at(1).name);
  const double with = MedianConfidentError(workspace, summary);
  fs::remove(dir.path() / "calibration" / "exposure.json");
  options.output = dir.path() / "without";
  const double without = MedianConfidentError(workspace, RestoreWorkspace(options));
  std::printf("EXIF exposure (8-bit JPEG): median error %.4f with the record, %.4f without\n", with, without);
  EXPECT_LT(with, 0.5 * without);
}

// coverage.lut beside the LUT is picked up: where it says no data constrained the nodes (the left half of
// the frustum here), the confidence is 0; where it says full coverage, the confidence is unchanged.
TEST(Restore, CoverageBesideTheLutLowersConfidenceWhereNoDataWas) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  RestoreOptions options = OptionsFor(workspace);
  options.output = dir.path() / "without";
  RestoreWorkspace(options);

  FrustumLut coverage(ReadLut(options.lut).grid());
  const FrustumLutGrid& grid = coverage.grid();
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        coverage.node(i, j, k).alpha = Eigen::Vector3d::Constant(i <= grid.nx / 2 ? 0.0 : 1.0);
      }
    }
  }
  fs::create_directories(dir.path() / "calibration");
  fs::copy_file(options.lut, dir.path() / "calibration" / "lut.lut");
  WriteLut(coverage, dir.path() / "calibration" / "coverage.lut");
  options.lut = dir.path() / "calibration" / "lut.lut";
  options.output = dir.path() / "with";
  const RestoreSummary summary = RestoreWorkspace(options);
  EXPECT_EQ(summary.coverage, dir.path() / "calibration" / "coverage.lut");

  const cv::Mat before = cv::imread((dir.path() / "without_confidence" / "frame_0000.png").string());
  const cv::Mat after = cv::imread((summary.confidence_output / "frame_0000.png").string());
  ASSERT_FALSE(before.empty());
  ASSERT_FALSE(after.empty());
  const cv::Rect left(0, 0, before.cols / 2 - 1, before.rows), right(before.cols / 2 + 10, 0, before.cols / 2 - 10, before.rows);
  EXPECT_GT(cv::mean(before(left))[1], 100.0);
  EXPECT_EQ(cv::countNonZero(after(left).reshape(1)), 0);
  EXPECT_EQ(cv::norm(before(right), after(right), cv::NORM_INF), 0.0);
}

TEST(Restore, LutForAnotherImageSizeIsAnErrorNamingTheLut) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  FrustumLut lut = ReadLut(workspace / "ground_truth" / "true.lut");
  FrustumLutGrid grid = lut.grid();
  grid.image_width = 400;
  grid.image_height = 300;
  WriteLut(FrustumLut(grid), dir.path() / "other.lut");
  RestoreOptions options = OptionsFor(workspace);
  options.lut = dir.path() / "other.lut";
  try {
    RestoreWorkspace(options);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("other.lut: the LUT is for 400x300 images but camera 1 is 200x150"),
              std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(workspace / "lutex"));
}

TEST(Restore, MissingImageIsAnErrorBeforeAnythingIsWritten) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  fs::remove(workspace / "images" / "frame_0003.png");
  try {
    RestoreWorkspace(OptionsFor(workspace));
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("frame_0003.png: no such image"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(workspace / "lutex"));
}

// Files the restored images of `workspace` are written as (temporaries included).
std::vector<fs::path> RestoredFiles(const fs::path& workspace) {
  std::vector<fs::path> files;
  if (!fs::exists(workspace / "lutex")) return files;
  for (const auto& entry : fs::recursive_directory_iterator(workspace / "lutex")) {
    if (entry.is_regular_file()) files.push_back(entry.path().filename());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A wrong-size, wrong-depth or not-an-image file among the images stops restore before its first write,
// naming the file (its header shows it); with skip_bad_images the others are restored and it is listed.
TEST(Restore, AnImageWhoseHeaderIsWrongStopsRestoreBeforeAnythingIsWritten) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  const std::vector<std::pair<std::string, std::string>> faults = {
      {"wrong size", "frame_0003.png: the image is 20x10 but its camera is 200x150"},
      {"wrong depth", "frame_0003.png: the image has 8-bit samples but the encoding is linear16"},
      {"truncated header", "frame_0003.png: not a readable PNG image (truncated header)"}};
  const fs::path bad = workspace / "images" / "frame_0003.png";
  const cv::Mat original = cv::imread(bad.string(), cv::IMREAD_UNCHANGED);
  for (const auto& [fault, message] : faults) {
    if (fault == "wrong size") cv::imwrite(bad.string(), cv::Mat(10, 20, CV_16UC3, cv::Scalar::all(1000)));
    if (fault == "wrong depth") cv::imwrite(bad.string(), cv::Mat(150, 200, CV_8UC3, cv::Scalar::all(100)));
    if (fault == "truncated header") {
      cv::imwrite(bad.string(), original);
      fs::resize_file(bad, 20);
    }
    try {
      RestoreWorkspace(OptionsFor(workspace));
      FAIL() << fault;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << fault << ": " << error.what();
    }
    EXPECT_TRUE(RestoredFiles(workspace).empty()) << fault;
  }
  RestoreOptions options = OptionsFor(workspace);
  options.skip_bad_images = true;
  const RestoreSummary summary = RestoreWorkspace(options);
  EXPECT_EQ(summary.num_images, 7u);
  ASSERT_EQ(summary.bad_images.size(), 1u);
  EXPECT_NE(summary.bad_images[0].find("frame_0003.png: not a readable PNG image"), std::string::npos);
  EXPECT_FALSE(fs::exists(workspace / "lutex" / "restored" / "frame_0003.png"));
  EXPECT_TRUE(fs::exists(workspace / "lutex" / "restored" / "frame_0004.png"));
}

// A file whose header is sound but whose pixels are cut off is found only when decoded: restore stops
// there naming it, every output written before it complete (no temporaries), or skips it when asked.
TEST(Restore, AnImageTruncatedBehindItsHeaderStopsRestoreWithCompleteOutputs) {
  testing::TempDir dir;
  const fs::path workspace = Simulated(dir.path());
  const fs::path bad = workspace / "images" / "frame_0005.png";
  fs::resize_file(bad, fs::file_size(bad) / 2);
  RestoreOptions options = OptionsFor(workspace);
  options.num_threads = 1;
  try {
    RestoreWorkspace(options);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("frame_0005.png: not a readable image"), std::string::npos) << error.what();
  }
  for (const fs::path& file : RestoredFiles(workspace)) {
    EXPECT_EQ(file.string().find(".tmp"), std::string::npos) << file;
    EXPECT_NE(file.string().find("frame_000"), std::string::npos) << file;
    if (file.extension() == ".png" && fs::exists(workspace / "lutex" / "restored" / file)) {
      EXPECT_FALSE(ReadLinearImage(workspace / "lutex" / "restored" / file, ImageEncoding::kLinear16).empty());
    }
  }
  options.skip_bad_images = true;
  const RestoreSummary summary = RestoreWorkspace(options);
  EXPECT_EQ(summary.num_images, 7u);
  ASSERT_EQ(summary.bad_images.size(), 1u);
  EXPECT_NE(summary.bad_images[0].find("frame_0005.png"), std::string::npos);
}

}  // namespace
}  // namespace lutex
