// Simulator speed: one 640 x 480 frame with two spot lights in clear water (shadows, backscatter), the
// per-camera backscatter table, and the true LUT on a 40 x 30 x 10 grid; the baseline measured in the
// same run is a plain ray cast of the same frame (depth + normal + face id). Not a test.
//
//   simulate_benchmark [--repeats 3] [--num-threads 0]

#include <algorithm>
#include <chrono>
#include <iostream>

#include "bench/bench_options.h"
#include "lib/geometry/look_at.h"
#include "lib/model/simulator.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/util/parallel_for.h"

namespace {

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "simulate_benchmark [--repeats 3] [--num-threads 0]");
  using namespace lutex;
  const int repeats = args.Int("--repeats", 3);
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();
  const Mesh seafloor = MakeSyntheticSeafloor(SyntheticSeafloorOptions());
  LightRig rig;
  for (double x : {-0.4, 0.4}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0, 0);
    light.intensity = Eigen::Vector3d::Constant(15.0 / (4 * M_PI));
    light.profile = BeamProfile::kCyclesSpot;
    rig.lights.push_back(light);
  }
  Water water;
  water.absorption = Eigen::Vector3d(0.35, 0.05, 0.02);
  water.scattering = Eigen::Vector3d(0.04, 0.045, 0.05);
  water.anisotropy_g = 0.88;
  SimulatorOptions options;
  options.num_threads = num_threads;
  const Simulator simulator(seafloor, rig, water, SurfaceAlbedo::FromVertexColors(seafloor), options);
  const Camera camera = Camera::Pinhole(1, 640, 480, 320, 320);
  const CameraRays rays(camera, num_threads);
  const Rigid3d cam_from_world =
      CamFromWorldLookingAt(Eigen::Vector3d(0.3, 0.2, 2.0), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
  const RaycastScene scene(seafloor);
  GeometryMapsOptions map_options;
  map_options.num_threads = num_threads;

  auto start = std::chrono::steady_clock::now();
  const BackscatterTable table = simulator.MakeBackscatterTable(rays);
  const double table_seconds = lutex::bench::SecondsSince(start);
  double frame = 1e30, raycast = 1e30, lut = 1e30;
  FrustumLutGrid grid;
  grid.image_width = 640;
  grid.image_height = 480;
  for (int r = 0; r < repeats; ++r) {
    start = std::chrono::steady_clock::now();
    const cv::Mat image = simulator.Render(rays, table, cam_from_world);
    frame = std::min(frame, lutex::bench::SecondsSince(start));
    start = std::chrono::steady_clock::now();
    const GeometryMaps maps = scene.Render(rays, cam_from_world, map_options);
    raycast = std::min(raycast, lutex::bench::SecondsSince(start));
    start = std::chrono::steady_clock::now();
    const FrustumLut true_lut = simulator.TrueLut(camera, grid);
    lut = std::min(lut, lutex::bench::SecondsSince(start));
  }
  std::cout << "mesh " << seafloor.NumFaces() << " faces, 640x480, 2 spot lights, clear water, " << num_threads
            << " threads, best of " << repeats << "\n"
            << "backscatter table (once per camera): " << table_seconds << " s\n"
            << "simulated frame: " << frame << " s\n"
            << "plain ray cast of the same frame (baseline): " << raycast << " s\n"
            << "ratio frame / ray cast: " << frame / raycast << "\n"
            << "true LUT 40x30x10: " << lut << " s\n";
  return 0;
}
