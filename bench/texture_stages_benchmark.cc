// Texturing at 12 MP, stage by stage: a simulated dive of 24 images of 4000 x 3000 (8-bit sRGB PNG, three
// lines at 1.5 m) over a 5.6 x 3.6 m seafloor of 1.6 M faces, the size of the workspace COLMAP's
// `mesh_texturer` was compared on (issue 19). In a child process that does nothing else, each stage of
// `lutex texture` is run through the library and its time and peak resident memory are taken (the peak is
// reset between stages: Linux's /proc/self/clear_refs); then, in another child, `lutex texture` as a
// whole. Plain decoding of the same images, in the same run, is the baseline. Not a test.
//
//   texture_stages_benchmark [--images 24] [--width 4000] [--num-threads 0] [--keep 0]
//
// --keep 1 leaves the simulated workspace in /tmp/lutex_texture_stages_benchmark/W, to run another
// texturer on it (README, 'Performance').

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench/bench_dive.h"
#include "bench/bench_folder.h"
#include "bench/bench_options.h"
#include "bench/bench_texture.h"
#include "bench/measure_in_child.h"
#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "colmap_integration/stages/workspace_views.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"
#include "texturing/face_adjacency.h"
#include "texturing/gltf_export.h"
#include "texturing/texture_baker.h"

namespace {

namespace fs = std::filesystem;

constexpr int kStages = 6;
constexpr const char* kStageNames[kStages] = {"read mesh, BVH, model",     "visibility", "view selection",
                                              "seam levelling",            "charts, atlas, colours, fill",
                                              "write GLB (PNG pages)"};

struct Stages {
  double seconds[kStages] = {};
  double stage_peak_mib[kStages] = {};
  double peak_mib = 0.0;  // filled by InChild (after a reset of the peak, only the last stage's)
  double decode_seconds = 0.0;
  double faces = 0.0;
  double texels = 0.0;
  double total_seconds = 0.0;
};

// Peak resident set since the last reset (VmHWM), MiB.
double PeakMib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

// Starts a new peak at the current resident set.
void ResetPeak() { std::ofstream("/proc/self/clear_refs") << "5"; }

void SimulateDive12Mp(const fs::path& root, int images, int width, int num_threads) {
  const int height = width * 3 / 4;
  const double focal = 0.625 * width;  // 77 degrees across: 2.4 x 1.8 m of floor at 1.5 m
  lutex::bench::SimulateDive(
      root, R"({"synthetic": {"size": [5.6, 3.6], "cell_size": 0.005, "relief": 0.1}})",
      R"({"model": "PINHOLE", "width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) +
          R"(, "params": [)" + std::to_string(focal) + ", " + std::to_string(focal) + ", " +
          std::to_string(width / 2.0) + ", " + std::to_string(height / 2.0) + "]}",
      R"({"pattern": "lawnmower", "x": [-1.8, 1.8], "y": [-1.0, 1.0], "lines": 3, "images_per_line": )" +
          std::to_string(std::max(1, images / 3)) + R"(, "altitude": 1.5})",
      num_threads);
}

Stages MeasureStages(const fs::path& workspace, int num_threads) {
  using namespace lutex;
  Stages stages;
  stages.decode_seconds = bench::DecodeSeconds(workspace, num_threads);
  ResetPeak();
  auto start = std::chrono::steady_clock::now();
  const auto end_stage = [&](int stage) {
    stages.seconds[stage] = bench::SecondsSince(start);
    stages.stage_peak_mib[stage] = PeakMib();
    ResetPeak();
    start = std::chrono::steady_clock::now();
  };
  const LoadedDive dive(workspace, workspace / "scene" / "mesh.ply");
  WorkspaceViewsOptions images;
  images.images = workspace / "images";
  const WorkspaceViews found = FindWorkspaceViews(dive.workspace(), dive.model(), images, "texture");
  const ViewImageSource source = found.Source();
  const ViewRaycaster raycaster(dive.scene());
  const FaceAdjacency adjacency(dive.mesh());
  end_stage(0);

  TextureBakingOptions options;
  options.num_threads = num_threads;
  FaceViewCandidatesOptions visibility = options.visibility;
  visibility.num_threads = num_threads;
  ChosenViews chosen{FindFaceViewCandidates(dive.mesh(), adjacency, found.views, raycaster, source, visibility),
                     {}, {}, {}, 0.0, 0.0};
  end_stage(1);
  chosen.selection = SelectViews(chosen.candidates, adjacency, options.selection);
  end_stage(2);
  TexelFusionOptions fusion = options.fusion;
  fusion.num_threads = num_threads;
  chosen.corrections = LevelSeams(dive.mesh(), adjacency, found.views, raycaster, source, chosen.candidates,
                                  chosen.selection.view_of_face, fusion, options.levelling, &chosen.levelling);
  end_stage(3);
  std::vector<std::uint32_t> all_faces(dive.mesh().faces.size());
  for (std::size_t f = 0; f < all_faces.size(); ++f) all_faces[f] = static_cast<std::uint32_t>(f);
  std::vector<std::uint32_t> source_vertex;
  TextureBakingSummary summary;
  const TexturedMesh textured =
      BakeFaces(dive.mesh(), found.views, raycaster, source, chosen, all_faces, options, source_vertex, summary);
  end_stage(4);
  WriteGltf(textured, workspace.parent_path() / "stages.glb");
  end_stage(5);
  stages.faces = static_cast<double>(dive.mesh().faces.size());
  stages.texels = static_cast<double>(summary.page_texels);
  return stages;
}

Stages MeasureWhole(const fs::path& workspace, int num_threads) {
  using namespace lutex;
  Stages stages;
  bench::TextureOwnImages(workspace, workspace.parent_path() / "whole.glb", num_threads, &stages.total_seconds);
  return stages;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "texture_stages_benchmark [--images 24] [--width 4000] [--num-threads 0] [--keep 0]");
  using namespace lutex;
  const int images = args.Int("--images", 24);
  const int width = args.Int("--width", 4000);
  const int num_threads = ResolveNumThreads(args.Int("--num-threads", 0));
  const bool keep = args.Int("--keep", 0) != 0;
  args.CheckAllRead();
  SetLogLevel(LogLevel::kWarning);
  const lutex::bench::BenchFolder folder("lutex_texture_stages_benchmark");
  const fs::path root = folder.path();
  bench::InChild<Stages>([&] {
    SimulateDive12Mp(root, images, width, num_threads);
    return Stages{};
  });
  const Stages stages = bench::InChild<Stages>([&] { return MeasureStages(root / "W", num_threads); });
  const Stages whole = bench::InChild<Stages>([&] { return MeasureWhole(root / "W", num_threads); });
  std::printf("texture stages benchmark: %d threads, %d images of %d x %d, %.2f M faces, atlas %.1f Mtexels\n",
              num_threads, 3 * std::max(1, images / 3), width, width * 3 / 4, stages.faces / 1e6, stages.texels / 1e6);
  std::printf("plain decoding of the images: %.2f s\n", stages.decode_seconds);
  std::printf("%-32s %10s %12s\n", "stage", "time [s]", "peak [MiB]");
  double total = 0.0, peak = 0.0;
  for (int s = 0; s < kStages; ++s) {
    std::printf("%-32s %10.2f %12.0f\n", kStageNames[s], stages.seconds[s], stages.stage_peak_mib[s]);
    total += stages.seconds[s];
    peak = std::max(peak, stages.stage_peak_mib[s]);
  }
  std::printf("%-32s %10.2f %12.0f   (ratio to decoding %.1f)\n", "all stages", total, peak,
              total / stages.decode_seconds);
  std::printf("%-32s %10.2f %12.0f   (ratio to decoding %.1f)\n", "lutex texture as a whole", whole.total_seconds,
              whole.peak_mib, whole.total_seconds / stages.decode_seconds);
  if (keep) {
    std::printf("the workspace is kept in %s\n", (root / "W").c_str());
  } else {
    fs::remove_all(root);
  }
  return 0;
}
