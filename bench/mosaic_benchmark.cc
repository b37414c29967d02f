// The mosaic of a synthetic dive as its surveyed area doubles and quadruples: a lawnmower survey at 2 m
// altitude (640 x 480, 8-bit sRGB PNG, 1 m between images, 3 lines 2 m apart) over a seafloor 6 m wide and
// 10, 20 or 40 m long (2 cm mesh cells: 0.3, 0.6, 1.2 M faces), mapped at 5 mm. For each: `lutex mosaic`
// time per output megapixel and peak memory (resident set, in a child process that does nothing else),
// against plain decoding of the same images in the same run, and the most faces a block's piece held
// (texturing/tile_views.h). Not a test.
//
//   mosaic_benchmark [--num-threads 0] [--tile-size 1024] [--image-cache MiB] [--gdal-cache MiB] [--keep 0]
//                    [--runs 1]
//
// --runs N runs `lutex mosaic` N times per area, each in its own child, and prints the median time and
// peak, with the lowest and highest peak: single runs' peaks differ by up to a tenth (measure_in_child.h).
//
// --keep 1 leaves the simulated dives in /tmp/lutex_mosaic_benchmark/dive_N/W, to run `lutex mosaic` on
// them under a profiler.
//
// --image-cache sets `lutex mosaic`'s decoded-picture cache and --gdal-cache GDAL's block cache while
// the GeoTIFFs are written (defaults: the command's). Each is a budget: these small images and mosaics
// fit in the defaults, which then fill with the area up to them.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "bench/measure_in_child.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/mosaic_workspace.h"
#include "lib/image/image_io.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"

namespace {

namespace fs = std::filesystem;

struct Measurement {
  double seconds = 0.0;
  double peak_mib = 0.0;
  double megapixels = 0.0;
  double tiles = 0.0;
  double image_reads = 0.0;
  double images = 0.0;
  double piece_faces = 0.0;
};

void SimulateMosaicDive(const fs::path& root, double length, int num_threads) {
  const int images_per_line = static_cast<int>(length);
  lutex::bench::SimulateDive(
      root,
      R"({"synthetic": {"size": [)" + std::to_string(length + 2.0) + R"(, 6], "cell_size": 0.02, "relief": 0.2}})",
      R"({"model": "PINHOLE", "width": 640, "height": 480, "params": [400, 400, 320, 240]})",
      R"({"pattern": "lawnmower", "x": [)" + std::to_string(-0.5 * (length - 1.0)) + ", " +
          std::to_string(0.5 * (length - 1.0)) + R"(], "y": [-2, 2], "lines": 3, "images_per_line": )" +
          std::to_string(images_per_line) + R"(, "altitude": 2})",
      num_threads);
}

Measurement Mosaic(const fs::path& workspace, int num_threads, int tile_size, std::size_t cache_bytes,
                   std::size_t gdal_cache_bytes) {
  using namespace lutex;
  Measurement measurement;
  MosaicOptions options;
  options.workspace = workspace;
  options.mesh = workspace / "scene" / "mesh.ply";
  options.views.images = workspace / "images";
  options.gsd = 0.005;
  options.output = workspace / "ortho.tif";
  options.dem = workspace / "dem.tif";
  options.ortho.tile_size = tile_size;
  options.picture_cache_bytes = cache_bytes;
  options.gdal_cache_bytes = gdal_cache_bytes;
  options.ortho.baking.num_threads = num_threads;
  const auto start = std::chrono::steady_clock::now();
  const MosaicSummary summary = MosaicWorkspace(options);
  measurement.seconds = bench::SecondsSince(start);
  measurement.megapixels = double(summary.mosaic.num_cells) / 1e6;
  measurement.tiles = double(summary.mosaic.num_tiles);
  measurement.image_reads = double(summary.mosaic.tile_view_reads);
  measurement.images = double(summary.mosaic.num_views);
  measurement.piece_faces = double(summary.mosaic.max_piece_faces);
  return measurement;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "mosaic_benchmark [--num-threads 0] [--tile-size 1024] [--image-cache MiB] [--gdal-cache MiB] [--keep 0] [--runs 1]");
  using namespace lutex;
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  const int tile_size = args.Int("--tile-size", 1024);
  const int cache_mib = args.Int("--image-cache", int(kDefaultPictureCacheBytes >> 20));
  const bool keep = args.Int("--keep", 0) != 0;
  const int runs = std::max(1, args.Int("--runs", 1));
  const int gdal_cache_mib = args.Int("--gdal-cache", int(MosaicOptions().gdal_cache_bytes >> 20));
  args.CheckAllRead();
  SetLogLevel(LogLevel::kWarning);
  const lutex::bench::BenchFolder folder("lutex_mosaic_benchmark");
  const fs::path root = folder.path();
  std::printf("mosaic benchmark: %d threads, tiles of %d pixels, image cache %d MiB, GDAL cache %d MiB, 5 mm GSD; "
              "mosaic: median of %d run(s)\n",
              num_threads, tile_size, cache_mib, gdal_cache_mib, runs);
  std::printf("%6s %7s %8s %6s %7s %11s %11s %13s %8s %11s %13s %13s\n", "area", "images", "Mpixels", "tiles", "reads",
              "decode [s]", "mosaic [s]", "s/Mpixel", "ratio", "peak [MiB]", "(runs' range)", "piece faces");
  for (const int factor : {1, 2, 4}) {
    const fs::path dive = root / ("dive_" + std::to_string(factor));
    bench::InChild<Measurement>([&] {
      SimulateMosaicDive(dive, 10.0 * factor, num_threads);
      return Measurement{};
    });
    const double decode_seconds = bench::DecodeSeconds(dive / "W", num_threads);
    bench::PeakSpread spread;
    const Measurement m = bench::InChildren<Measurement>(
        runs,
        [&] { return Mosaic(dive / "W", num_threads, tile_size, std::size_t(cache_mib) << 20,
                            std::size_t(gdal_cache_mib) << 20); },
        &spread);
    std::printf("%5dx %7.0f %8.1f %6.0f %7.0f %11.2f %11.2f %13.3f %8.1f %11.0f %6.0f - %4.0f %13.0f\n", factor,
                m.images, m.megapixels, m.tiles, m.image_reads, decode_seconds, m.seconds, m.seconds / m.megapixels,
                m.seconds / decode_seconds, m.peak_mib, spread.lowest_mib, spread.highest_mib, m.piece_faces);
    std::fflush(stdout);
    if (!keep) fs::remove_all(dive);
  }
  if (!keep) fs::remove_all(root);
  return 0;
}
