// Restoration speed against plain I/O, measured in the same run on the same images: a simulated
// workspace of N 8-bit sRGB PNG images (default 24 of 1280 x 960), then (a) decode + encode every image
// (read, linearise, encode, write: what any tool that touches the images pays), (a') the same writing
// two images per input (the I/O restore cannot avoid) and (b) `lutex restore`
// (read, ray-cast, look up, restore, smooth the noise, write image and confidence map). Reports both and the
// ratio, then where restore's time goes: every stage timed on its own on one thread (read, ray cast, restore
// arithmetic, noise-adaptive smoothing, write image, write confidence map), and what taking forward scattering out of an image
// costs on top (`--remove-forward-scatter` with coastal water). Not a test.
//
//   restore_benchmark [--images 24] [--width 1280] [--num-threads 0]

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "colmap_integration/io/confidence_map_io.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/image/image_io.h"
#include "lib/geometry/mesh_io.h"
#include "lib/lut/lut_file.h"
#include "lib/model/water.h"
#include "lib/raycast/forward_scatter_removal.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/restoration/noise_adaptive_smoothing.h"
#include "lib/util/parallel_for.h"

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "restore_benchmark [--images 24] [--width 1280] [--num-threads 0]");
  using namespace lutex;
  namespace fs = std::filesystem;
  const int images = args.Int("--images", 24);
  const int width = args.Int("--width", 1280);
  const int height = width * 3 / 4;
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();
  const lutex::bench::BenchFolder folder("lutex_restore_benchmark");
  const fs::path root = folder.path();
  bench::SimulateDive(root, R"({"synthetic": {"size": [12, 10]}})",
                      R"({"model": "PINHOLE", "width": )" + std::to_string(width) + R"(, "height": )" +
                          std::to_string(height) + R"(, "params": [)" + std::to_string(width / 2) + ", " +
                          std::to_string(width / 2) + ", " + std::to_string(width / 2) + ", " +
                          std::to_string(height / 2) + "]}",
                      R"({"lines": 1, "images_per_line": )" + std::to_string(images) +
                          R"(, "x": [-4, 4], "y": [0, 0], "altitude": 2})",
                      num_threads);

  const SparseModel model = ReadSparseModel(root / "W" / "sparse" / "0");
  auto start = std::chrono::steady_clock::now();
  std::vector<const Image*> list;
  for (const auto& entry : model.images) list.push_back(&entry.second);
  ParallelFor(list.size(), num_threads, [&](std::size_t i) {
    const cv::Mat linear = ReadLinearImage(root / "W" / "images" / list[i]->name, ImageEncoding::kSrgb8);
    WriteLinearImage(linear, root / "copy" / list[i]->name, ImageEncoding::kSrgb8);
  });
  const double plain = bench::SecondsSince(start);

  // The least I/O restore itself does: decode, and encode two images of the size (the restored image and
  // its confidence map; here the input written twice).
  start = std::chrono::steady_clock::now();
  ParallelFor(list.size(), num_threads, [&](std::size_t i) {
    const cv::Mat linear = ReadLinearImage(root / "W" / "images" / list[i]->name, ImageEncoding::kSrgb8);
    WriteLinearImage(linear, root / "copy" / list[i]->name, ImageEncoding::kSrgb8);
    WriteLinearImage(linear, root / "copy2" / list[i]->name, ImageEncoding::kSrgb8);
  });
  const double two_outputs = bench::SecondsSince(start);

  RestoreOptions restore;
  restore.workspace = root / "W";
  restore.mesh = root / "W" / "scene" / "mesh.ply";
  restore.lut = root / "W" / "ground_truth" / "true.lut";
  restore.num_threads = num_threads;
  start = std::chrono::steady_clock::now();
  RestoreWorkspace(restore);
  const double restored = bench::SecondsSince(start);

  // The stages of restore on one thread, each timed on its own over the same images.
  const Mesh mesh = ReadMesh(restore.mesh);
  const RaycastScene scene(mesh);
  const FrustumLut lut = ReadLut(restore.lut);
  const CameraRays rays(model.cameras.begin()->second, 1);
  GeometryMapsOptions maps_options;
  maps_options.num_threads = 1;
  double read = 0.0, cast = 0.0, arithmetic = 0.0, smoothing = 0.0, write = 0.0, write_confidence = 0.0, forward_scatter = 0.0;
  const ForwardScatter coastal = ForwardScatter::Of(*WaterPreset("coastal"));
  GeometryMaps maps;
  RestoredImage result;
  for (const Image* image : list) {
    start = std::chrono::steady_clock::now();
    const cv::Mat linear = ReadLinearImage(root / "W" / "images" / image->name, ImageEncoding::kSrgb8);
    read += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    scene.Render(rays, image->cam_from_world, maps_options, &maps);
    cast += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    const cv::Mat without_forward_scatter = WithoutForwardScatter(linear, maps, rays, coastal, restore.restoration.saturation_level);
    forward_scatter += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    RestoreImage(linear, maps, rays, lut, restore.restoration, nullptr, &result);
    arithmetic += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    result.albedo = SmoothNoiseAdaptively(result.albedo, maps.depth == maps.depth, restore.smoothing);
    smoothing += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    WriteLinearImage(result.albedo, root / "stages" / image->name, ImageEncoding::kSrgb8);
    write += bench::SecondsSince(start);
    start = std::chrono::steady_clock::now();
    WriteConfidenceMap(result.confidence, root / "stages_confidence" / image->name);
    write_confidence += bench::SecondsSince(start);
  }
  const double stages = read + cast + arithmetic + smoothing + write + write_confidence;
  const auto share = [&](const char* name, double seconds) {
    std::cout << "  " << name << ": " << seconds / images << " s per image (" << 100.0 * seconds / stages << " %)\n";
  };

  std::cout << images << " images of " << width << "x" << height << ", " << num_threads << " threads\n"
            << "decode + encode: " << plain << " s (" << plain / images << " s per image)\n"
            << "decode + encode twice (restore's own I/O: image and confidence map): " << two_outputs << " s ("
            << two_outputs / images << " s per image)\n"
            << "lutex restore (incl. reading mesh and LUT, BVH, confidence maps): " << restored << " s ("
            << restored / images << " s per image)\n"
            << "ratio restore / plain I/O: " << restored / plain << "\n"
            << "ratio restore / restore's own I/O: " << restored / two_outputs << "\n"
            << "restore's stages, one thread:\n";
  share("read and linearise", read);
  share("ray cast (depth, normal)", cast);
  share("restore (LUT lookup, albedo, confidence)", arithmetic);
  share("noise-adaptive smoothing", smoothing);
  share("write restored image", write);
  share("write confidence map", write_confidence);
  std::cout << "  with --remove-forward-scatter (coastal water), also: " << forward_scatter / images
            << " s per image (" << 100.0 * forward_scatter / stages << " % more)\n";
  std::cout << "ratio all stages / (read + write restored image): " << stages / (read + write) << "\n"
            << "ratio all stages / (read + write both images): " << stages / (read + write + write_confidence) << "\n";
  fs::remove_all(root);
  return 0;
}
