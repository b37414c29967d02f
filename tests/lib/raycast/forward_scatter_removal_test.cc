#include "lib/raycast/forward_scatter_removal.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

// A floor at z = 0 seen from 2 m above, looking down and 30 degrees forward: ranges from about 2 to 3.5 m.
struct TiltedView {
  TiltedView() {
    camera.camera_id = 1;
    camera.model_id = CameraModelId::kPinhole;
    camera.width = 240;
    camera.height = 180;
    camera.params = {200, 200, 120, 90};
    Mesh floor;
    floor.vertices = {{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}};
    floor.faces = {{0, 1, 2}, {0, 2, 3}};
    const Eigen::Vector3d centre(0, 0, 2);
    cam_from_world = CamFromWorldLookingAt(centre, Eigen::Vector3d(0, std::sin(0.52), -std::cos(0.52)), Eigen::Vector3d(0, 1, 0));
    const RaycastScene scene(floor);
    const CameraRays rays(camera);
    maps = scene.Render(rays, cam_from_world);
    camera_centre = centre;
  }
  Camera camera;
  Rigid3d cam_from_world;
  GeometryMaps maps;
  Eigen::Vector3d camera_centre;
};

// A checkerboard albedo of 20-pixel squares, as seen (radiance proportional to albedo).
cv::Mat Checkerboard(int rows, int cols) {
  cv::Mat signal(rows, cols, CV_32FC3);
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const bool bright = ((row / 20) + (col / 20)) % 2 == 0;
      signal.at<cv::Vec3f>(row, col) = bright ? cv::Vec3f(0.5f, 0.7f, 0.4f) : cv::Vec3f(0.04f, 0.08f, 0.05f);
    }
  }
  return signal;
}

TEST(ForwardScatterRemoval, TheRangeIsTheDistanceToTheSurfaceAlongTheRay) {
  const TiltedView view;
  const CameraRays rays(view.camera);
  const cv::Mat range = RangeAlongRays(view.maps, rays);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  for (const cv::Point pixel : {cv::Point(0, 0), cv::Point(120, 90), cv::Point(239, 179), cv::Point(17, 150)}) {
    // The ray through the pixel's centre meets z = 0 at distance 2 / -direction_z from the camera.
    const Eigen::Vector3d direction =
        (world_from_cam.rotation * rays.Direction(pixel.x, pixel.y).cast<double>()).normalized();
    ASSERT_LT(direction.z(), 0.0);
    EXPECT_NEAR(range.at<float>(pixel), 2.0 / -direction.z(), 1e-4) << pixel;
  }
}

// What the water did (AddForwardScatter over the ray-cast ranges) is undone, and pixels clipped in the
// recording stay clipped.
TEST(ForwardScatterRemoval, UndoesTheWaterAndLeavesClippedPixelsClipped) {
  const TiltedView view;
  const CameraRays rays(view.camera);
  const ForwardScatter scatter{Eigen::Vector3d(0.35, 0.4, 0.38), 0.9};
  const cv::Mat signal = Checkerboard(static_cast<int>(view.camera.height), static_cast<int>(view.camera.width));
  const cv::Mat recorded = AddForwardScatter(signal, RangeAlongRays(view.maps, rays),
                                             MakeForwardScatterKernel(scatter.anisotropy_g, 200.0), scatter.scattering);
  const cv::Mat restored = WithoutForwardScatter(recorded, view.maps, rays, scatter, 0.98);
  cv::Mat before, after;
  cv::absdiff(recorded, signal, before);
  cv::absdiff(restored, signal, after);
  EXPECT_GT(cv::norm(before, cv::NORM_INF), 0.05);
  EXPECT_LT(cv::norm(after, cv::NORM_INF), 0.01);

  // A light's reflection clips a 10 x 10 block in the recording: it stays at or above the level.
  cv::Mat clipped = recorded.clone();
  const cv::Rect glint(100, 80, 10, 10);
  clipped(glint).setTo(cv::Scalar(1.0, 1.0, 1.0));
  const cv::Mat corrected = WithoutForwardScatter(clipped, view.maps, rays, scatter, 0.98);
  for (int row = glint.y; row < glint.br().y; ++row) {
    for (int col = glint.x; col < glint.br().x; ++col) {
      EXPECT_EQ(corrected.at<cv::Vec3f>(row, col), cv::Vec3f(1.0f, 1.0f, 1.0f)) << row << " " << col;
    }
  }
  // Without scattering nothing changes.
  EXPECT_EQ(cv::norm(WithoutForwardScatter(clipped, view.maps, rays, ForwardScatter{}, 0.98), clipped, cv::NORM_INF), 0.0);
}

// The LUT's β at each pixel's surface, at the pixel's depth, times the image's gain; 0 off the surface.
TEST(ForwardScatterRemoval, TheBackscatterAtTheSurfacesIsTheLutsAtTheirDepth) {
  TiltedView view;
  // The upper rows see past the horizon of a floor 2 m below at 30 degrees: make some see nothing.
  view.maps.depth.rowRange(0, 5).setTo(std::numeric_limits<float>::quiet_NaN());
  const FrustumLutGrid grid = testing::LutGrid(6, 5, 4, 0.5, 5.0, static_cast<int>(view.camera.width),
                                               static_cast<int>(view.camera.height));
  FrustumLut lut(grid);
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        lut.node(i, j, k).alpha = Eigen::Vector3d::Constant(1.0);
        lut.node(i, j, k).beta = Eigen::Vector3d(0.01 * (i + 1), 0.02 * (j + 1), 0.005 * (k + 1));
      }
    }
  }
  const cv::Mat backscatter = BackscatterAtSurfaces(lut, view.maps, 2.5);
  for (const cv::Point pixel : {cv::Point(3, 2), cv::Point(120, 90), cv::Point(239, 179), cv::Point(17, 150)}) {
    const float depth = view.maps.depth.at<float>(pixel);
    const cv::Vec3f value = backscatter.at<cv::Vec3f>(pixel);
    if (!std::isfinite(depth)) {
      EXPECT_EQ(value, cv::Vec3f(0, 0, 0)) << pixel;
      continue;
    }
    const Eigen::Vector3d expected = 2.5 * lut.Lookup(pixel.x + 0.5, pixel.y + 0.5, depth).beta;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(value[c], expected[c], 1e-5 * (1.0 + expected[c])) << pixel;
  }
}

}  // namespace
}  // namespace lutex
