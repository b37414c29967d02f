// Correspondence extraction for self-calibration (lutex calibrate --correspondences) on a simulated
// survey: N images (default 100) of about 1 MP (1152 x 864, 8-bit sRGB PNG), a lawnmower of 5 lines at
// 2 m over a 12 x 10 m synthetic seafloor, two spot lights in clear water. Measures, in the same run,
// plain decoding of the N images (the least any pass over them costs) and ExtractSurveyCorrespondences
// (two streamed passes: SLIC superpixels per image, then every image looks up its askers' samples),
// and reports both, the ratio and the number of correspondences. Not a test.
//
//   correspondence_benchmark [--images 100] [--num-threads 0]

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/calibration/survey_correspondences.h"
#include "colmap_integration/io/workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "correspondence_benchmark [--images 100] [--num-threads 0]");
  using namespace lutex;
  namespace fs = std::filesystem;
  const int images = args.Int("--images", 100);
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();
  const int lines = 5;
  const int per_line = std::max(1, images / lines);
  SetLogLevel(LogLevel::kWarning);
  const lutex::bench::BenchFolder folder("lutex_correspondence_benchmark");
  const fs::path root = folder.path();
  bench::SimulateDive(root, R"({"synthetic": {"size": [12, 10]}})",
                      R"({"model": "PINHOLE", "width": 1152, "height": 864, "params": [720, 720, 576, 432]})",
                      R"({"pattern": "lawnmower", "x": [-4.5, 4.5], "y": [-3, 3], "lines": )" + std::to_string(lines) +
                          R"(, "images_per_line": )" + std::to_string(per_line) + R"(, "altitude": 2})",
                      num_threads);

  const Workspace workspace = FindWorkspace(root / "W");
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  std::vector<std::string> names;
  for (const auto& [id, image] : model.images) names.push_back(image.name);
  auto start = std::chrono::steady_clock::now();
  ParallelFor(names.size(), num_threads,
              [&](std::size_t i) { ReadLinearImage(workspace.images_dir / names[i], ImageEncoding::kSrgb8); });
  const double decode = bench::SecondsSince(start);

  start = std::chrono::steady_clock::now();
  const RaycastScene scene(ReadMesh(root / "W" / "scene" / "mesh.ply"));
  SurveyCorrespondenceOptions options;
  options.num_threads = num_threads;
  const SurveyCorrespondences found = ExtractSurveyCorrespondences(workspace.images_dir, model, scene, options);
  const double extract = bench::SecondsSince(start);

  std::cout << names.size() << " images of 1152 x 864, " << num_threads << " threads\n"
            << "decode: " << decode << " s\n"
            << "correspondence extraction (incl. mesh, BVH, two passes): " << extract << " s, "
            << found.num_samples << " superpixel samples, " << found.correspondences.size() << " correspondences\n"
            << "ratio extraction / decode: " << extract / decode << "\n";
  fs::remove_all(root);
  return 0;
}
