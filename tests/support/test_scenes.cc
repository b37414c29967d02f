#include "tests/support/test_scenes.h"

#include <algorithm>
#include <cmath>

#include "lib/calibration/calibrator.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/image/image_io.h"
#include "lib/model/sensor.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex::testing {

Water ClearWater() {
  Water water = *WaterPreset("clear");
  water.anisotropy_g = 0.88;
  return water;
}

LightRig TwoCosineLights(double offset, double intensity, double exponent) {
  LightRig rig;
  for (double x : {-offset, offset}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0, 0);
    light.intensity = Eigen::Vector3d::Constant(intensity);
    light.profile = BeamProfile::kCosinePower;
    light.exponent = exponent;
    rig.lights.push_back(light);
  }
  return rig;
}

FrustumLutGrid LutGrid(int nx, int ny, int nz, double z_near, double z_far, int width, int height) {
  FrustumLutGrid grid;
  grid.nx = nx;
  grid.ny = ny;
  grid.nz = nz;
  grid.z_near = z_near;
  grid.z_far = z_far;
  grid.image_width = width;
  grid.image_height = height;
  return grid;
}

std::vector<double> SortedConfidentErrors(const RestoredImage& restored, const Eigen::Vector3d& albedo) {
  std::vector<double> errors;
  for (int row = 0; row < restored.albedo.rows; ++row) {
    for (int col = 0; col < restored.albedo.cols; ++col) {
      for (int c = 0; c < 3; ++c) {
        if (restored.confidence.at<cv::Vec3f>(row, col)[c] < 0.5f) continue;
        errors.push_back(std::abs(restored.albedo.at<cv::Vec3f>(row, col)[c] - albedo[c]));
      }
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

cv::Mat NoisySrgb8Frame(const Simulator& simulator, const CameraRays& rays, const Rigid3d& cam_from_world,
                        std::uint64_t index, std::uint64_t seed, const std::filesystem::path& folder) {
  SensorOptions sensor;
  sensor.exposure = 2.0;
  sensor.shot_noise = 0.01;
  sensor.read_noise = 0.002;
  sensor.seed = seed;
  const auto path = folder / ("frame_" + std::to_string(index) + ".png");
  WriteLinearImage(ApplySensor(simulator.Render(rays, cam_from_world), sensor, index), path, ImageEncoding::kSrgb8);
  return ReadLinearImage(path, ImageEncoding::kSrgb8);
}

std::vector<double> HeldOutGreyPlaneErrors(const ObservationSet& observations, const Camera& camera, double z_near,
                                           double z_far, const Eigen::Vector3d& eye, const Eigen::Vector3d& forward,
                                           const std::filesystem::path& folder) {
  const int width = static_cast<int>(camera.width), height = static_cast<int>(camera.height);
  const FrustumLutGrid grid = LutGrid(8, 6, 6, z_near, z_far, width, height);
  CalibrationOptions options;
  options.grid = grid;
  options.levels = {{2, 2}, {4, 3}, {8, 6}};
  const Simulator weighting(Mesh(), PointLightAtCamera(), ClearWater(), SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  const CalibrationResult result = Calibrate(observations, weighting.TrueLut(camera, grid), options);
  const Mesh plane = MakeHeightFieldMesh([](double, double) { return 0.0; }, -10, 10, -10, 10, 2, 2);
  const Eigen::Vector3d grey = Eigen::Vector3d::Constant(0.35);
  const Simulator held_out(plane, TwoCosineLights(0.3, 1.0, 1.5), ClearWater(), SurfaceAlbedo::Constant(grey));
  const CameraRays rays(camera);
  const Rigid3d pose = CamFromWorldLookingAt(eye, forward.normalized(), Eigen::Vector3d(0, -1, 0));
  const cv::Mat image = NoisySrgb8Frame(held_out, rays, pose, 99, 9, folder);
  const RaycastScene scene(plane);
  return SortedConfidentErrors(RestoreImage(image, scene.Render(rays, pose), rays, result.lut, RestorationOptions()), grey);
}

}  // namespace lutex::testing
