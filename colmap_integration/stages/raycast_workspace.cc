#include "colmap_integration/stages/raycast_workspace.h"

#include <iomanip>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <vector>


#include "colmap_integration/io/colmap_array.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/raycast/images_by_camera.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/io/workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/raycast/geometry_previews.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

void RaycastOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (mesh.empty()) throw OptionError("{mesh} is required");
}

namespace {

// What raycast reads and writes (output_policy.h).
InputsAndOutputs PathsOf(const RaycastOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(options.mesh, "the mesh");
  paths.AddOutput(options.output.empty() ? workspace.RaycastDir() : options.output);
  return paths;
}

}  // namespace

RaycastSummary RaycastWorkspace(const RaycastOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  return RaycastWorkspace(options, LoadedDive(options.workspace, options.mesh));
}

RaycastSummary RaycastWorkspace(const RaycastOptions& options, const LoadedDive& dive) {
  options.Check();
  const InputsAndOutputs paths = PathsOf(options, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  CheckStageMemory("raycast", dive, options.num_threads, kRaycastStageBytesPerPixel, options.memory_limit_bytes);
  const auto start = std::chrono::steady_clock::now();
  const Workspace& workspace = dive.workspace();
  const SparseModel& model = dive.model();
  const Mesh& mesh = dive.mesh();
  const RaycastScene& scene = dive.scene();
  LogInfo() << "read " << model.images.size() << " images, " << model.cameras.size() << " cameras, "
            << mesh.NumFaces() << " faces";

  RaycastSummary summary;
  summary.output = options.output.empty() ? workspace.RaycastDir() : options.output;
  summary.num_faces = mesh.NumFaces();

  summary.wrote_previews = options.write_previews;
  const auto outputs_of = [&](const Image& image) {
    std::vector<fs::path> outputs = {summary.output / "depth_maps" / (image.name + ".geometric.bin"),
                                     summary.output / "normal_maps" / (image.name + ".geometric.bin")};
    if (options.write_previews) {
      outputs.push_back(summary.output / "previews" / (image.name + ".depth.png"));
      outputs.push_back(summary.output / "previews" / (image.name + ".normal.png"));
    }
    return outputs;
  };
  const SparseModel todo = options.skip_done ? WithoutDoneImages(model, outputs_of) : model;
  summary.num_skipped = model.images.size() - todo.images.size();

  std::vector<double> hit_fractions;
  std::mutex hit_fractions_mutex;
  ForEachImageWithMaps(todo, scene, options.num_threads, "raycast",
                       [&](const Image& image, const CameraRays&, const GeometryMaps& maps, int) {
    const std::vector<fs::path> outputs = outputs_of(image);
    const double hit_fraction =
        static_cast<double>(cv::countNonZero(maps.depth == maps.depth)) / static_cast<double>(maps.depth.total());
    WriteColmapArray(ReplaceNanWithZero(maps.depth), outputs[0]);
    WriteColmapArray(ReplaceNanWithZero(maps.normal), outputs[1]);
    if (options.write_previews) {
      WriteEncodedImage(DepthPreview(maps.depth), outputs[2]);
      WriteEncodedImage(NormalPreview(maps.normal), outputs[3]);
    }
    std::lock_guard<std::mutex> lock(hit_fractions_mutex);
    hit_fractions.push_back(hit_fraction);
  });

  summary.num_images = hit_fractions.size();
  for (double fraction : hit_fractions) summary.mean_hit_fraction += fraction;
  if (!hit_fractions.empty()) summary.mean_hit_fraction /= static_cast<double>(hit_fractions.size());
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintRaycastSummary(std::ostream& out, const RaycastSummary& summary) {
  out << "raycast: " << summary.num_images << " images against " << summary.num_faces << " faces in "
            << std::fixed << std::setprecision(1) << summary.seconds << " s; " << std::setprecision(0)
            << 100.0 * summary.mean_hit_fraction << " % of pixels see the mesh\n"
            << "  depth maps:  " << (summary.output / "depth_maps").string() << "\n"
            << "  normal maps: " << (summary.output / "normal_maps").string() << "\n";
  if (summary.wrote_previews) out << "  previews:    " << (summary.output / "previews").string() << "\n";
}

}  // namespace lutex
