// Texturing a synthetic dive: a lawnmower survey of N images (default 200, 640 x 480, 8-bit sRGB PNG)
// over a 20 x 12.5 m seafloor of 1.25 M faces (simulated by lutex simulate), then the same area with 2N
// images (twice as many survey lines). For each: `lutex texture` time and peak memory (resident set,
// measured in a child process that does nothing else), against plain decoding of the same images in the
// same run (the least any texturer pays). Not a test.
//
//   texture_benchmark [--images 200] [--num-threads 0]

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "bench/bench_texture.h"
#include "bench/measure_in_child.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "lib/image/image_io.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"

namespace {

namespace fs = std::filesystem;

struct Measurement {
  double seconds = 0.0;
  double peak_mib = 0.0;
  double decode_seconds = 0.0;
  double texels = 0.0;
  double faces = 0.0;
};

// The 20 x 12.5 m, 1.25 M-face dive with `lines` survey lines.
void SimulateTextureDive(const fs::path& root, int lines, int images_per_line, int num_threads) {
  lutex::bench::SimulateDive(root, R"({"synthetic": {"size": [20, 12.5], "cell_size": 0.02, "relief": 0.2}})",
                             R"({"model": "PINHOLE", "width": 640, "height": 480, "params": [400, 400, 320, 240]})",
                             R"({"pattern": "lawnmower", "x": [-8.5, 8.5], "y": [-5, 5], "lines": )" +
                                 std::to_string(lines) + R"(, "images_per_line": )" + std::to_string(images_per_line) +
                                 R"(, "altitude": 2})",
                             num_threads);
}

Measurement Texture(const fs::path& workspace, int num_threads) {
  using namespace lutex;
  Measurement measurement;
  measurement.decode_seconds = bench::DecodeSeconds(workspace, num_threads);
  const TextureSummary summary =
      bench::TextureOwnImages(workspace, workspace / "model.glb", num_threads, &measurement.seconds);
  measurement.texels = static_cast<double>(summary.baking.page_texels);
  measurement.faces = static_cast<double>(summary.baking.num_faces);
  return measurement;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "texture_benchmark [--images 200] [--num-threads 0]");
  using namespace lutex;
  const int images = args.Int("--images", 200);
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();
  SetLogLevel(LogLevel::kWarning);
  const lutex::bench::BenchFolder folder("lutex_texture_benchmark");
  const fs::path root = folder.path();
  const int images_per_line = 20;
  const int lines = std::max(1, images / images_per_line);
  std::printf("texture benchmark: %d threads; %d and %d images of 640 x 480 over 1.25 M faces\n", num_threads,
              lines * images_per_line, 2 * lines * images_per_line);
  std::printf("%8s %12s %12s %8s %12s %10s\n", "images", "decode [s]", "texture [s]", "ratio", "peak [MiB]", "Mtexels");
  for (const int factor : {1, 2}) {
    const fs::path dive = root / ("dive_" + std::to_string(factor));
    bench::InChild<Measurement>([&] {
      SimulateTextureDive(dive, factor * lines, images_per_line, num_threads);
      return Measurement{};
    });
    const Measurement m = bench::InChild<Measurement>([&] { return Texture(dive / "W", num_threads); });
    std::printf("%8d %12.2f %12.2f %8.1f %12.0f %10.1f\n", factor * lines * images_per_line, m.decode_seconds,
                m.seconds, m.seconds / m.decode_seconds, m.peak_mib, m.texels / 1e6);
    std::fflush(stdout);
  }
  fs::remove_all(root);
  return 0;
}
