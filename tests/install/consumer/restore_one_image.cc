// Uses lutex as a library: simulates one view of a grey plane under two spot lights in clear water, writes
// the simulator's true LUT to `argv[1]`, loads it back as a calibrated LUT would be, restores the image and
// compares the restored albedo with the known one. Exits 0 when the median error is below 1 percentage
// point, printing it.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/lut/lut_file.h"
#include "lib/model/simulator.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/restoration/restorer.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: restore_one_image LUT_TO_WRITE\n");
    return 2;
  }
  using namespace lutex;
  const Mesh plane = MakeHeightFieldMesh([](double, double) { return 0.0; }, -5, 5, -5, 5, 2, 2);
  LightRig rig;
  for (double x : {-0.3, 0.3}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0, 0);
    light.profile = BeamProfile::kCosinePower;
    light.exponent = 1.5;
    rig.lights.push_back(light);
  }
  const Water water = *WaterPreset("clear");
  const Eigen::Vector3d albedo(0.5, 0.35, 0.2);
  const Simulator simulator(plane, rig, water, SurfaceAlbedo::Constant(albedo));
  const Camera camera = Camera::Pinhole(1, 160, 120, 100, 100);
  const CameraRays rays(camera);
  const Rigid3d cam_from_world =
      CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
  FrustumLutGrid grid;
  grid.image_width = 160;
  grid.image_height = 120;
  WriteLut(simulator.TrueLut(camera, grid), argv[1]);

  const FrustumLut lut = ReadLut(argv[1]);
  const RaycastScene scene(plane);
  const RestoredImage restored =
      RestoreImage(simulator.Render(rays, cam_from_world), scene.Render(rays, cam_from_world), rays, lut,
                   RestorationOptions());
  std::vector<double> errors;
  for (int row = 0; row < 120; ++row) {
    for (int col = 0; col < 160; ++col) {
      for (int c = 0; c < 3; ++c) {
        if (restored.confidence.at<cv::Vec3f>(row, col)[c] < 0.5f) continue;
        errors.push_back(std::abs(restored.albedo.at<cv::Vec3f>(row, col)[c] - albedo[c]));
      }
    }
  }
  if (errors.size() < 160 * 120) {
    std::fprintf(stderr, "only %zu confident pixel-channels\n", errors.size());
    return 1;
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  const double median = errors[errors.size() / 2];
  std::printf("restored %zu pixel-channels, median error %.3f pp\n", errors.size(), 100 * median);
  return median < 0.01 ? 0 : 1;
}
