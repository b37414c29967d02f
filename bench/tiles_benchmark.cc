// 3D Tiles of a growing survey: the same seafloor and survey pattern over an area 1x, 2x and 4x as large
// (more faces and more images, at the same density). For each: `lutex tiles` and `lutex texture` (the
// single GLB) time and peak memory (resident set, each in a child process that does nothing else),
// against plain decoding of the same images in the same run, and the tile count. What tiling promises:
// peak memory that does not grow with the area. Not a test.
//
//   tiles_benchmark [--images 50] [--tile-faces 100000] [--image-cache MiB] [--num-threads 0] [--runs 1]
//                   [--base-area 1] [--texture 1]
//
// --runs N runs `lutex tiles` N times per area, each in its own child, and prints the median time and
// peak, with the lowest and highest peak: single runs' peaks differ by up to a tenth (measure_in_child.h).
//
// --image-cache sets `lutex tiles`' decoded-picture cache (default: the command's). The cache is a budget:
// it fills up to it and no further, so with the default the small images of the 1x area all fit and the
// 4x area's fill it more; a budget the 1x area already fills shows what grows with the area besides it.
//
// The areas are 1x, 2x and 4x of --base-area units of 10 x 6.25 m (312 k faces, --images images each). At
// the defaults the largest area is the texture benchmark's dive: 20 x 12.5 m, 1.25 M faces, 200 images of
// 640 x 480; with --base-area 4 the smallest is, and the others are its double and quadruple (the issue's
// x1, x2 and x4: 1.25, 2.5 and 5 M faces). --texture 0 leaves out the single GLB, whose memory grows with
// the area (about 8 GB at 5 M faces).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "bench/bench_texture.h"
#include "bench/measure_in_child.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "colmap_integration/stages/tiles_workspace.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"

namespace {

namespace fs = std::filesystem;

struct Measurement {
  double seconds = 0.0;
  double peak_mib = 0.0;
  double tiles = 0.0;
  double faces = 0.0;
  double piece_faces = 0.0;  // the most faces a leaf's views were chosen on (texturing/tile_views.h)
};

// A 10 x 6.25 m patch of seafloor (0.02 m cells: 312 k faces) per unit of area, `width` x `height` units,
// surveyed by lawnmower lines 1.25 m apart at 2 m altitude.
void SimulateArea(const fs::path& root, int width, int height, int images_per_line, int num_threads) {
  const double size_x = 10.0 * width, size_y = 6.25 * height;
  const int lines = 4 * height;
  lutex::bench::SimulateDive(
      root,
      R"({"synthetic": {"size": [)" + std::to_string(size_x) + ", " + std::to_string(size_y) +
          R"(], "cell_size": 0.02, "relief": 0.2}})",
      R"({"model": "PINHOLE", "width": 640, "height": 480, "params": [400, 400, 320, 240]})",
      R"({"pattern": "lawnmower", "x": [)" + std::to_string(-0.5 * size_x + 1.5) + ", " +
          std::to_string(0.5 * size_x - 1.5) + R"(], "y": [)" + std::to_string(-0.5 * size_y + 0.6) + ", " +
          std::to_string(0.5 * size_y - 0.6) + R"(], "lines": )" + std::to_string(lines) +
          R"(, "images_per_line": )" + std::to_string(images_per_line * width) + R"(, "altitude": 2})",
      num_threads);
}

Measurement Tiles(const fs::path& workspace, std::size_t tile_faces, std::size_t cache_bytes, int num_threads) {
  using namespace lutex;
  TilesOptions options;
  options.workspace = workspace;
  options.mesh = workspace / "scene" / "mesh.ply";
  options.views.images = workspace / "images";
  options.output = workspace.parent_path() / "tiles";
  options.tree.max_faces = tile_faces;
  options.picture_cache_bytes = cache_bytes;
  options.baking.num_threads = num_threads;
  options.georeference.enu_origin = "54.32,10.14,-20";
  const auto start = std::chrono::steady_clock::now();
  const TilesSummary summary = TilesWorkspace(options);
  Measurement measurement;
  measurement.seconds = bench::SecondsSince(start);
  measurement.tiles = double(summary.num_tiles);
  measurement.faces = double(summary.num_faces);
  measurement.piece_faces = double(summary.max_piece_faces);
  return measurement;
}

Measurement Texture(const fs::path& workspace, int num_threads) {
  using namespace lutex;
  Measurement measurement;
  const TextureSummary summary =
      bench::TextureOwnImages(workspace, workspace.parent_path() / "model.glb", num_threads, &measurement.seconds);
  measurement.tiles = 1.0;
  measurement.faces = double(summary.baking.num_faces);
  return measurement;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "tiles_benchmark [--images 50] [--tile-faces 100000] [--image-cache MiB] [--num-threads 0] [--runs 1] [--base-area 1] [--texture 1]");
  using namespace lutex;
  const int images = args.Int("--images", 50);
  const int tile_faces = args.Int("--tile-faces", 100000);
  const int cache_mib = args.Int("--image-cache", int(kDefaultPictureCacheBytes >> 20));
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  const int runs = std::max(1, args.Int("--runs", 1));
  const int base_area = args.Int("--base-area", 1);
  const bool with_texture = args.Int("--texture", 1) != 0;
  args.CheckAllRead();
  if (base_area != 1 && base_area != 2 && base_area != 4) {
    std::fprintf(stderr, "tiles_benchmark: --base-area is 1, 2 or 4 units of 10 x 6.25 m\n");
    return 2;
  }
  SetLogLevel(LogLevel::kWarning);
  const lutex::bench::BenchFolder folder("lutex_tiles_benchmark");
  const fs::path root = folder.path();
  const int images_per_line = std::max(1, images / 4);
  std::printf("tiles benchmark: %d threads, %d faces a tile, image cache %d MiB; areas 1x, 2x, 4x of %d x 10 x 6.25 m "
              "(%d x 312 k faces, %d images); tiles: median of %d run(s)\n",
              num_threads, tile_faces, cache_mib, base_area, base_area, base_area * 4 * images_per_line, runs);
  std::printf("%5s %8s %7s %11s %10s %7s %11s %13s %12s %10s %11s\n", "area", "Mfaces", "images", "decode [s]",
              "tiles [s]", "ratio", "tiles [MiB]", "(runs' range)", "texture [s]", "ratio", "tex. [MiB]");
  for (int factor : {1, 2, 4}) {
    // Units of 10 x 6.25 m laid out as near a square as they go: 1 x 1, 2 x 1, 2 x 2, 4 x 2, 4 x 4.
    const int units = factor * base_area;
    int width = 1;
    while (width * width < units) width *= 2;
    const fs::path dive = root / ("area_" + std::to_string(factor));
    bench::InChild<Measurement>([&] {
      SimulateArea(dive, width, units / width, images_per_line, num_threads);
      return Measurement{};
    });
    const double decode = bench::DecodeSeconds(dive / "W", num_threads);
    bench::PeakSpread spread;
    const Measurement tiles = bench::InChildren<Measurement>(
        runs, [&] { return Tiles(dive / "W", tile_faces, std::size_t(cache_mib) << 20, num_threads); }, &spread);
    const Measurement texture =
        with_texture ? bench::InChild<Measurement>([&] { return Texture(dive / "W", num_threads); }) : Measurement{};
    std::printf("%4dx %8.2f %7d %11.2f %10.2f %7.1f %11.0f %6.0f - %4.0f %12.2f %10.1f %11.0f   (%0.f tiles; views "
                "chosen on pieces of at most %.0f k faces)\n",
                factor, tiles.faces / 1e6, 4 * images_per_line * units, decode, tiles.seconds,
                tiles.seconds / decode, tiles.peak_mib, spread.lowest_mib, spread.highest_mib, texture.seconds,
                texture.seconds / decode, texture.peak_mib, tiles.tiles, tiles.piece_faces / 1e3);
    std::fflush(stdout);
    fs::remove_all(dive);
  }
  fs::remove_all(root);
  return 0;
}
