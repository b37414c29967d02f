#include "lib/model/shading.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/model/simulator.h"

namespace lutex {
namespace {

// Two Cycles spots 0.4 m beside the camera (the shared Blender rig).
LightRig TwoSpots() {
  LightRig rig;
  for (const double x : {-0.4, 0.4}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0, 0);
    light.profile = BeamProfile::kCyclesSpot;
    light.spot_size_rad = 110.0 * M_PI / 180.0;
    light.spot_blend = 0.5;
    rig.lights.push_back(light);
  }
  return rig;
}

// In air, planes 0.8 m away tilted by -25, 0 and 25 degrees, lit by two spots beside the camera, rendered
// by the simulator: with the rig's shading a render is exactly alpha(x) cos_theta rho with alpha(x) the
// true LUT's formula (Simulator::SignalFactor), a function of the point alone, at every pixel and tilt.
// With shading from the camera centre the same alpha is off by up to tens of percent on the tilted
// planes, where one spot's cone edge makes one light dominate: the error the rig's shading removes.
TEST(Shading, WithTheRigTheSignalFactorIsIndependentOfTheSurfaceTilt) {
  const LightRig rig = TwoSpots();
  Shading with_rig;
  with_rig.rig = rig;
  const Shading camera_centred;
  const Eigen::Vector3d rho(0.6, 0.5, 0.4);
  const Camera camera = Camera::Pinhole(1, 64, 48, 36, 36);
  const CameraRays rays(camera);
  const Rigid3d cam_from_world =
      CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 0.8), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
  double worst_rig = 0.0, worst_camera_centred = 0.0;
  for (const double tilt_deg : {-25.0, 0.0, 25.0}) {
    const double slope = std::tan(tilt_deg * M_PI / 180.0);
    const Mesh plane = MakeHeightFieldMesh([slope](double x, double) { return slope * x; }, -5, 5, -5, 5, 2, 2);
    const Simulator simulator(plane, rig, Water::Air(), SurfaceAlbedo::Constant(rho));
    const cv::Mat image = simulator.Render(rays, cam_from_world);
    const GeometryMaps maps = simulator.RenderGeometry(rays, cam_from_world, GeometryMapsOptions());
    for (int row = 0; row < 48; ++row) {
      for (int col = 0; col < 64; ++col) {
        const float depth = maps.depth.at<float>(row, col);
        const cv::Vec3f observed = image.at<cv::Vec3f>(row, col);
        if (std::isnan(depth) || observed[0] < 1e-3f) continue;
        const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
        const Eigen::Vector3d point = depth / direction.z() * direction;
        const cv::Vec3f n = maps.normal.at<cv::Vec3f>(row, col);
        const Eigen::Vector3d normal(n[0], n[1], n[2]);
        const Eigen::Vector3d alpha = simulator.SignalFactor(point);
        for (int c = 0; c < 3; ++c) {
          const double restored_rig = observed[c] / (alpha[c] * with_rig.Cosine(point, normal));
          const double restored_camera = observed[c] / (alpha[c] * camera_centred.Cosine(point, normal));
          worst_rig = std::max(worst_rig, std::abs(restored_rig / rho[c] - 1.0));
          worst_camera_centred = std::max(worst_camera_centred, std::abs(restored_camera / rho[c] - 1.0));
        }
      }
    }
  }
  std::printf("worst relative albedo error: rig shading %.2e, camera-centred %.3f\n", worst_rig, worst_camera_centred);
  EXPECT_LT(worst_rig, 1e-4);
  EXPECT_GT(worst_camera_centred, 0.1);
}

TEST(Shading, OnePositionIsTheCosineTowardsIt) {
  Shading flash;
  flash.light_in_cam = Eigen::Vector3d(0.1, 0, 0);
  const Eigen::Vector3d point(0.1, 0.0, 1.0), normal(0, 0, -1);
  EXPECT_NEAR(flash.Cosine(point, normal), 1.0, 1e-12);
  EXPECT_NEAR(Shading().Cosine(point, normal), 1.0 / std::sqrt(1.01), 1e-12);
}

// Outside every spot's cone no light of the rig reaches the point: the camera centre stands in.
TEST(Shading, OutsideEveryConeFallsBackToTheCameraCentre) {
  Shading with_rig;
  with_rig.rig = TwoSpots();
  const Eigen::Vector3d point(0.0, 5.0, 0.1), normal = Eigen::Vector3d(0, -1, -1).normalized();
  EXPECT_NEAR(with_rig.Cosine(point, normal), Shading().Cosine(point, normal), 1e-12);
}

// Restoration's float cosine equals the double one to float precision, with one position and with a rig,
// over points across a frustum and tilted normals.
TEST(Shading, FloatCosineEqualsDoubleCosine) {
  Shading flash, with_rig;
  flash.light_in_cam = Eigen::Vector3d(0.1, -0.05, 0);
  with_rig.rig = TwoSpots();
  for (const Shading* shading : {&flash, &with_rig}) {
    for (const double x : {-1.0, 0.0, 0.7}) {
      for (const double z : {0.5, 2.0, 6.0}) {
        const Eigen::Vector3d point(x * z, 0.3 * z, z), normal = Eigen::Vector3d(0.3, -0.2, -1).normalized();
        EXPECT_NEAR(shading->Cosine(Eigen::Vector3f(point.cast<float>()), Eigen::Vector3f(normal.cast<float>())),
                    shading->Cosine(point, normal), 1e-6);
      }
    }
  }
}

}  // namespace
}  // namespace lutex
