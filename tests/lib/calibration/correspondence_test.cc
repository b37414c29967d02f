// Self-calibration from correspondences on scenes the project's simulator rendered (seeded, noisy, 8-bit
// sRGB): superpixel samples matched across views, solved without any known colour (grey-world scale)
// or together with known colours.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/calibrator.h"
#include "lib/calibration/correspondence_views.h"
#include "lib/calibration/superpixel_samples.h"
#include "lib/geometry/look_at.h"
#include "lib/image/image_io.h"
#include "lib/model/sensor.h"
#include "lib/model/simulator.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/restoration/restorer.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

constexpr int kWidth = 160, kHeight = 120;

// 8-bit sRGB quantisation of a linear image, as a camera's JPEG would have it.
cv::Mat Quantised(const cv::Mat& linear) {
  return DecodeLinearImage(EncodeLinearImage(linear, ImageEncoding::kSrgb8), ImageEncoding::kSrgb8);
}

struct Frame {
  Rigid3d cam_from_world;
  cv::Mat image;
  GeometryMaps maps;
  std::vector<SurfaceSample> samples;
};

// In air, a Gaussian spot at the camera (a strong light cone with dark corners) over a flat floor of many
// colour patches, seen looking down from 1.2-1.9 m.
class InAirCorrespondences : public ::testing::Test {
 protected:
  InAirCorrespondences()
      : floor_(MakeSyntheticSeafloor(Floor())),
        scene_(floor_),
        camera_(Camera::Pinhole(1, kWidth, kHeight, 110, 110)),
        rays_(camera_),
        simulator_(floor_, Rig(), Water::Air(), SurfaceAlbedo::FromVertexColors(floor_)) {}

  static SyntheticSeafloorOptions Floor() {
    SyntheticSeafloorOptions options;
    options.size_x = 6;
    options.size_y = 6;
    options.relief = 0.0;
    options.num_boulders = 0;
    options.patch_size = 0.25;
    options.seed = 3;
    return options;
  }

  static LightRig Rig() {
    Light light;
    light.profile = BeamProfile::kGaussian;
    light.sigma_rad = 0.35;
    light.intensity = Eigen::Vector3d(2.0, 1.8, 1.6);
    return {{light}};
  }

  static FrustumLutGrid Grid() { return testing::LutGrid(8, 6, 3, 1.1, 2.0, kWidth, kHeight); }

  Frame Render(const Eigen::Vector3d& centre, std::uint64_t index) const {
    Frame frame;
    frame.cam_from_world = CamFromWorldLookingAt(centre, Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 1, 0));
    SensorOptions sensor;
    sensor.exposure = 3.0;
    sensor.shot_noise = 0.01;
    sensor.read_noise = 0.002;
    sensor.seed = 21;
    frame.image = Quantised(ApplySensor(simulator_.Render(rays_, frame.cam_from_world), sensor, index));
    frame.maps = scene_.Render(rays_, frame.cam_from_world);
    frame.samples = SampleSuperpixels(frame.image, frame.maps, rays_);
    return frame;
  }

  // Survey: a 4 x 4 grid of positions 0.3 m apart at three altitudes.
  std::vector<Frame> Survey() const {
    std::vector<Frame> frames;
    std::uint64_t index = 0;
    for (double altitude : {1.25, 1.5, 1.85}) {
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          frames.push_back(Render(Eigen::Vector3d(0.3 * (i - 1.5), 0.3 * (j - 1.5), altitude), index++));
        }
      }
    }
    return frames;
  }

  // Every sample of every frame matched in at most `partners` other frames that see it, nearest first.
  std::vector<CorrespondenceObservation> Correspondences(const std::vector<Frame>& frames, std::size_t partners) const {
    std::vector<CorrespondenceObservation> correspondences;
    for (std::size_t a = 0; a < frames.size(); ++a) {
      const Rigid3d world_from_cam = frames[a].cam_from_world.Inverse();
      std::vector<std::size_t> others;
      for (std::size_t b = 0; b < frames.size(); ++b) {
        if (b != a) others.push_back(b);
      }
      const auto centre = [&](std::size_t f) { return frames[f].cam_from_world.Inverse().translation; };
      std::stable_sort(others.begin(), others.end(), [&](std::size_t x, std::size_t y) {
        return (centre(x) - centre(a)).norm() < (centre(y) - centre(a)).norm();
      });
      for (const SurfaceSample& sample : frames[a].samples) {
        const Eigen::Vector3d point_in_world = world_from_cam * sample.view.point_in_cam;
        const double footprint = sample.footprint_radius * sample.view.point_in_cam.z() / camera_.FocalLengthX();
        std::size_t found = 0;
        for (std::size_t b : others) {
          const ViewedImage other{frames[b].image, frames[b].maps, rays_, frames[b].cam_from_world};
          if (const auto view = ViewInOtherImage(point_in_world, footprint, other)) {
            correspondences.push_back({sample.view, *view, Eigen::Vector3d::Ones()});
            if (++found == partners) break;
          }
        }
      }
    }
    return correspondences;
  }

  Mesh floor_;
  RaycastScene scene_;
  Camera camera_;
  CameraRays rays_;
  Simulator simulator_;
};

// Restored albedo of a held-out frame against the truth after one least-squares scale per channel:
// returns the median absolute error over confident pixel-channels.
double ErrorAfterScale(const RestoredImage& restored, const cv::Mat& truth) {
  Eigen::Vector3d product = Eigen::Vector3d::Zero(), square = Eigen::Vector3d::Zero();
  for (int row = 0; row < truth.rows; ++row) {
    for (int col = 0; col < truth.cols; ++col) {
      for (int c = 0; c < 3; ++c) {
        if (restored.confidence.at<cv::Vec3f>(row, col)[c] < 0.5f) continue;
        product[c] += restored.albedo.at<cv::Vec3f>(row, col)[c] * truth.at<cv::Vec3f>(row, col)[c];
        square[c] += std::pow(restored.albedo.at<cv::Vec3f>(row, col)[c], 2);
      }
    }
  }
  const Eigen::Vector3d scale = product.cwiseQuotient(square);
  std::vector<double> errors;
  for (int row = 0; row < truth.rows; ++row) {
    for (int col = 0; col < truth.cols; ++col) {
      for (int c = 0; c < 3; ++c) {
        if (restored.confidence.at<cv::Vec3f>(row, col)[c] < 0.5f) continue;
        errors.push_back(std::abs(scale[c] * restored.albedo.at<cv::Vec3f>(row, col)[c] - truth.at<cv::Vec3f>(row, col)[c]));
      }
    }
  }
  EXPECT_GT(errors.size(), static_cast<std::size_t>(truth.total()));  // most pixel-channels are confident
  std::sort(errors.begin(), errors.end());
  std::printf("scale %.3f %.3f %.3f; error median %.4f p90 %.4f over %zu pixel-channels\n", scale.x(), scale.y(),
              scale.z(), errors[errors.size() / 2], errors[errors.size() * 9 / 10], errors.size());
  return errors[errors.size() / 2];
}

TEST_F(InAirCorrespondences, CorrespondencesAloneRestoreAHeldOutFrameWithin3PercentAfterScale) {
  const std::vector<Frame> frames = Survey();
  std::size_t samples = 0;
  for (const Frame& frame : frames) samples += frame.samples.size();
  ObservationSet observations;
  observations.correspondences = Correspondences(frames, 4);
  std::printf("%zu frames, %zu superpixel samples, %zu correspondences\n", frames.size(), samples,
              observations.correspondences.size());
  ASSERT_GT(observations.correspondences.size(), 2000u);

  CalibrationOptions options;
  options.grid = Grid();
  options.levels = {{2, 2}, {4, 3}, {8, 6}};
  options.in_air = true;
  options.grey_world_albedo = Eigen::Vector3d::Constant(0.3);
  const Simulator weighting(Mesh(), PointLightAtCamera(), Water::Air(), SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  const CalibrationResult result = Calibrate(observations, weighting.TrueLut(camera_, options.grid), options);
  std::printf("correspondence albedo rms %.4f %.4f %.4f, covered %.0f %%\n", result.summary.correspondence_albedo_rms.x(),
              result.summary.correspondence_albedo_rms.y(), result.summary.correspondence_albedo_rms.z(),
              100 * result.summary.covered_fraction);

  // Held out: between the survey's positions and altitudes.
  const Frame held_out = Render(Eigen::Vector3d(0.1, -0.2, 1.6), 99);
  const RestoredImage restored = RestoreImage(held_out.image, held_out.maps, rays_, result.lut, RestorationOptions());
  const cv::Mat truth = simulator_.RenderAlbedo(rays_, held_out.cam_from_world);
  EXPECT_LT(ErrorAfterScale(restored, truth), 0.03);
}

// The paper's experiment (Sec. 4.4): known colours everywhere but in a 4 x 4 block of nodes of the middle
// slab, where the LUT must come from smoothness alone, from correspondences alone (smoothness negligible),
// or from both. Error: the restored albedo of a held-out frame at that depth, where it is looked up from
// the region, against the truth.
TEST_F(InAirCorrespondences, CorrespondencesFillA4x4RegionWithoutKnownColours) {
  const std::vector<Frame> frames = Survey();
  const FrustumLutGrid grid = Grid();
  const auto in_region = [&](int node) {
    const int i = node % grid.NodesX(), j = (node / grid.NodesX()) % grid.NodesY(), k = node / (grid.NodesX() * grid.NodesY());
    return k == 1 && i >= 3 && i <= 6 && j >= 2 && j <= 5;
  };
  const FrustumLut layout(grid);
  ObservationSet known, all_known;
  std::size_t removed = 0;
  for (const Frame& frame : frames) {
    const cv::Mat albedo = simulator_.RenderAlbedo(rays_, frame.cam_from_world);
    for (int row = 2; row < kHeight; row += 4) {
      for (int col = 2; col < kWidth; col += 4) {
        const float z = frame.maps.depth.at<float>(row, col);
        if (!(z > 0.0f)) continue;
        const cv::Vec3f rho = albedo.at<cv::Vec3f>(row, col);
        const cv::Vec3f intensity = frame.image.at<cv::Vec3f>(row, col);
        KnownColorObservation observation;
        observation.pixel = Eigen::Vector2d(col + 0.5, row + 0.5);
        const Eigen::Vector3d direction = rays_.Direction(col, row).cast<double>();
        observation.point_in_cam = direction * (double(z) / direction.z());
        observation.intensity = Eigen::Vector3d(intensity[0], intensity[1], intensity[2]);
        observation.albedo = Eigen::Vector3d(rho[0], rho[1], rho[2]);
        const cv::Vec3f normal = frame.maps.normal.at<cv::Vec3f>(row, col);
        observation.cos_theta = std::abs(Eigen::Vector3d(normal[0], normal[1], normal[2]).dot(direction));  // light at the camera
        const NodeWeights weights = layout.Weights(observation.pixel.x(), observation.pixel.y(), z);
        bool touches_region = false;
        for (int n = 0; n < weights.count; ++n) touches_region |= weights.weight[n] > 0.0 && in_region(weights.node[n]);
        if (observation.intensity.maxCoeff() >= 0.98) continue;
        all_known.known_colors.push_back(observation);
        if (touches_region) {
          ++removed;
        } else {
          known.known_colors.push_back(observation);
        }
      }
    }
  }
  const std::vector<CorrespondenceObservation> correspondences = Correspondences(frames, 4);
  std::printf("%zu known-colour observations, %zu removed in the region, %zu correspondences\n",
              known.known_colors.size(), removed, correspondences.size());
  ASSERT_GT(removed, 500u);

  const Simulator weighting(Mesh(), PointLightAtCamera(), Water::Air(), SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  const FrustumLut reference = weighting.TrueLut(camera_, grid);
  // Held out, at the region's depth: restored albedo against the truth where lookups lean mostly (> 50 %)
  // on the region's nodes.
  const Frame held_out = Render(Eigen::Vector3d(0.1, -0.2, 1.55), 99);
  const cv::Mat truth = simulator_.RenderAlbedo(rays_, held_out.cam_from_world);
  const auto region_error = [&](bool with_correspondences, double smoothness, bool with_region = false) {
    ObservationSet observations = with_region ? all_known : known;
    if (with_correspondences) observations.correspondences = correspondences;
    CalibrationOptions options;
    options.grid = grid;
    options.levels = {{2, 2}, {4, 3}, {8, 6}};
    options.in_air = true;
    options.smoothness_scale = smoothness;
    // Each solve runs to convergence: the comparison is about what each constraint determines, not about
    // where the default early stop leaves a solution that started from the coarser level.
    options.max_iterations = 100;
    options.function_tolerance = 1e-6;
    const CalibrationResult result = Calibrate(observations, reference, options);
    const RestoredImage restored = RestoreImage(held_out.image, held_out.maps, rays_, result.lut, RestorationOptions());
    double sum = 0.0;
    std::size_t count = 0;
    for (int row = 0; row < kHeight; ++row) {
      for (int col = 0; col < kWidth; ++col) {
        const float z = held_out.maps.depth.at<float>(row, col);
        if (!(z > 0.0f)) continue;
        const NodeWeights weights = layout.Weights(col + 0.5, row + 0.5, z);
        double region_weight = 0.0;
        for (int n = 0; n < weights.count; ++n) region_weight += in_region(weights.node[n]) ? weights.weight[n] : 0.0;
        if (region_weight < 0.5) continue;
        for (int c = 0; c < 3; ++c) sum += std::abs(restored.albedo.at<cv::Vec3f>(row, col)[c] - truth.at<cv::Vec3f>(row, col)[c]);
        count += 3;
      }
    }
    EXPECT_GT(count, 3000u);
    return sum / double(count);
  };
  const double smooth_only = region_error(false, 0.01);
  const double correspondences_only = region_error(true, 1e-5);
  const double both = region_error(true, 0.01);
  const double known_everywhere = region_error(false, 0.01, true);
  std::printf("restored albedo MAE in the 4 x 4 region: smoothness only %.2f pp, correspondences only %.2f pp, both "
              "%.2f pp (known colours in the region too: %.2f pp)\n",
              100 * smooth_only, 100 * correspondences_only, 100 * both, 100 * known_everywhere);
  EXPECT_LT(both, smooth_only);
  EXPECT_LT(correspondences_only, smooth_only);
  EXPECT_LT(both, 0.08);
}

}  // namespace
}  // namespace lutex
