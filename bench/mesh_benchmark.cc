// lutex mesh (lib/geometry/sparse_surface.h) on simulated surveys of 12 MP images: a lawnmower at 2 m over
// a rolling seafloor (4000 x 3000 pixels, f = 3000 px: a 2.7 x 2 m footprint), with N images (default 100,
// then 2N) and 2000 sparse points per image as SfM would give them (lib/model/sparse_points.h, 1 mm noise: 1.5 px).
// For each: time and peak memory of the fit (resident set, in a child process that does nothing else) and
// the height error against the true terrain. The images themselves are not rendered: the fit reads only
// the model. Not a test.
//
//   mesh_benchmark [--images 100] [--num-threads 0]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "bench/bench_options.h"
#include "bench/measure_in_child.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/geometry/sparse_surface.h"
#include "lib/model/sparse_points.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"

namespace {

struct Measurement {
  double seconds = 0.0;
  double peak_mib = 0.0;
  double points = 0.0;
  double faces = 0.0;
  double median_error_mm = 0.0;
  double p95_error_mm = 0.0;
};

double Terrain(double x, double y) { return 0.3 * std::sin(0.8 * x) * std::cos(0.6 * y) + 0.02 * x; }

Measurement Fit(int images, int num_threads) {
  using namespace lutex;
  const int per_line = 20;
  const int lines = std::max(1, images / per_line);
  const double length = 0.9 * (per_line - 1), width = 1.5 * (lines - 1);
  const Mesh terrain = MakeHeightFieldMesh(Terrain, -0.5 * length - 3, 0.5 * length + 3, -0.5 * width - 3,
                                           0.5 * width + 3, static_cast<int>(length + 6) * 20,
                                           static_cast<int>(width + 6) * 20);
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 4000, 3000, 3000.0, 3000.0);
  std::uint32_t id = 1;
  for (int l = 0; l < lines; ++l) {
    for (int i = 0; i < per_line; ++i) {
      Image image;
      image.image_id = id++;
      image.camera_id = 1;
      const double x = -0.5 * length + 0.9 * i, y = -0.5 * width + 1.5 * l;
      image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(x, y, Terrain(x, y) + 2.0),
                                                   Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
      model.images[image.image_id] = image;
    }
  }
  SparsePointsOptions points;
  points.points_per_image = 2000;
  points.noise = 0.001;
  points.num_threads = num_threads;
  AddSimulatedSparsePoints(RaycastScene(terrain), points, &model);
  Measurement measurement;
  measurement.points = double(model.points3D.size());
  const auto start = std::chrono::steady_clock::now();
  const SparseSurface surface = SurfaceFromSparsePoints(model, Eigen::Vector3d::UnitZ(), SparseSurfaceOptions());
  measurement.seconds = bench::SecondsSince(start);
  measurement.faces = double(surface.mesh.faces.size());
  std::vector<double> errors;
  for (const Eigen::Vector3d& v : surface.mesh.vertices) {
    if (std::abs(v.x()) < 0.5 * length && std::abs(v.y()) < 0.5 * width + 0.5) {
      errors.push_back(std::abs(v.z() - Terrain(v.x(), v.y())));
    }
  }
  std::sort(errors.begin(), errors.end());
  if (!errors.empty()) {
    measurement.median_error_mm = 1000.0 * errors[errors.size() / 2];
    measurement.p95_error_mm = 1000.0 * errors[errors.size() * 95 / 100];
  }
  return measurement;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "mesh_benchmark [--images 100] [--num-threads 0]");
  using namespace lutex;
  const int images = args.Int("--images", 100);
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();
  SetLogLevel(LogLevel::kWarning);
  std::printf("mesh benchmark: %d threads; 12 MP images, 2000 sparse points each (the fit only, not the simulation)\n",
              num_threads);
  std::printf("%8s %10s %10s %10s %12s %14s %12s\n", "images", "points", "faces", "fit [s]", "peak [MiB]",
              "median [mm]", "p95 [mm]");
  for (const int factor : {1, 2}) {
    const Measurement m = bench::InChild<Measurement>([&] { return Fit(factor * images, num_threads); });
    std::printf("%8d %10.0f %10.0f %10.2f %12.0f %14.1f %12.1f\n", factor * images, m.points, m.faces, m.seconds,
                m.peak_mib, m.median_error_mm, m.p95_error_mm);
    std::fflush(stdout);
  }
  return 0;
}
