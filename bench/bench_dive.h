#pragma once

// The simulated dive the benchmarks run on: a scene description for lutex simulate with the given
// mesh, camera and survey (JSON objects, as in examples/scenes), two 15 W spot lights 0.4 m to the sides
// of the camera in clear water, and a noisy 8-bit sensor; simulated into ROOT/W. And the time to decode its
// images, the baseline of the benchmarks that read them.

#include <filesystem>
#include <fstream>
#include <string>

#include "bench/bench_options.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/simulate_workspace.h"
#include "lib/image/image_io.h"
#include "lib/util/parallel_for.h"

namespace lutex::bench {

inline void SimulateDive(const std::filesystem::path& root, const std::string& mesh_json,
                         const std::string& camera_json, const std::string& survey_json, int num_threads) {
  std::filesystem::create_directories(root);
  std::ofstream(root / "scene.json") << R"({"mesh": )" << mesh_json << R"(, "camera": )" << camera_json
                                     << R"(, "survey": )" << survey_json << R"(,
         "lights": [{"position": [-0.4, 0, 0], "power_W": 15, "profile": "cycles_spot"},
                    {"position": [0.4, 0, 0], "power_W": 15, "profile": "cycles_spot"}],
         "water": {"absorption": [0.35, 0.05, 0.02], "scattering": [0.04, 0.045, 0.05], "g": 0.88},
         "sensor": {"exposure": 4, "shot_noise": 0.01, "read_noise": 0.002}})";
  SimulateOptions simulate;
  simulate.scene = root / "scene.json";
  simulate.output = root / "W";
  simulate.num_threads = num_threads;
  SimulateWorkspace(simulate);
}

// Seconds to decode every registered image of the simulated workspace (8-bit sRGB PNG): the baseline a
// stage that reads them all is measured against, in the same run.
inline double DecodeSeconds(const std::filesystem::path& workspace, int num_threads) {
  const SparseModel model = ReadSparseModel(workspace / "sparse" / "0");
  std::vector<std::string> names;
  for (const auto& [id, image] : model.images) names.push_back(image.name);
  const auto start = std::chrono::steady_clock::now();
  ParallelFor(names.size(), num_threads,
              [&](std::size_t i) { ReadLinearImage(workspace / "images" / names[i], ImageEncoding::kSrgb8); });
  return SecondsSince(start);
}

}  // namespace lutex::bench
