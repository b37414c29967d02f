#include "colmap_integration/raycast_workspace.h"

#include <chrono>
#include <map>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/colmap_array.h"
#include "colmap_integration/sparse_model_io.h"
#include "colmap_integration/workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/raycast/geometry_previews.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/atomic_output.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

// Cameras with the same model, size and parameters share one ray table.
using CameraKey = std::tuple<int, std::uint64_t, std::uint64_t, std::vector<double>>;

void WritePng(const cv::Mat& picture, const fs::path& path) {
  AtomicOutputFile output(path);
  if (!cv::imwrite(output.temporary_path().string(), picture)) {
    throw std::runtime_error(path.string() + ": could not write the PNG");
  }
  output.Commit();
}

}  // namespace

void RaycastOptions::Check() const {
  if (workspace.empty()) throw std::invalid_argument("--workspace is required");
  if (mesh.empty()) throw std::invalid_argument("--mesh is required");
}

RaycastSummary RaycastWorkspace(const RaycastOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const Workspace workspace = FindWorkspace(options.workspace);
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  const Mesh mesh = ReadMesh(options.mesh);
  LogInfo() << "read " << model.images.size() << " images, " << model.cameras.size() << " cameras, "
            << mesh.NumFaces() << " faces";
  const RaycastScene scene(mesh);

  RaycastSummary summary;
  summary.output = options.output.empty() ? workspace.OutputDir() / "raycast" : options.output;
  summary.num_faces = mesh.NumFaces();

  std::map<CameraKey, std::vector<const Image*>> images_by_camera;
  for (const auto& entry : model.images) {
    const Camera& camera = model.cameras.at(entry.second.camera_id);
    images_by_camera[CameraKey(static_cast<int>(camera.model_id), camera.width, camera.height, camera.params)]
        .push_back(&entry.second);
  }

  ProgressReporter progress("raycast", model.images.size(), "images");
  std::vector<double> hit_fractions;
  for (const auto& [key, images] : images_by_camera) {
    const CameraRays rays(model.cameras.at(images.front()->camera_id), options.num_threads);
    std::vector<double> group_fractions(images.size());
    ParallelFor(images.size(), options.num_threads, [&](std::size_t i) {
      const Image& image = *images[i];
      GeometryMapsOptions map_options;
      map_options.face_id = false;
      map_options.num_threads = 1;  // parallel over images instead
      const GeometryMaps maps = scene.Render(rays, image.cam_from_world, map_options);
      group_fractions[i] = static_cast<double>(cv::countNonZero(maps.depth == maps.depth)) /
                           static_cast<double>(maps.depth.total());
      WriteColmapArray(ReplaceNanWithZero(maps.depth),
                       summary.output / "depth_maps" / (image.name + ".geometric.bin"));
      WriteColmapArray(ReplaceNanWithZero(maps.normal),
                       summary.output / "normal_maps" / (image.name + ".geometric.bin"));
      if (options.write_previews) {
        WritePng(DepthPreview(maps.depth), summary.output / "previews" / (image.name + ".depth.png"));
        WritePng(NormalPreview(maps.normal), summary.output / "previews" / (image.name + ".normal.png"));
      }
      progress.Advance();
    });
    hit_fractions.insert(hit_fractions.end(), group_fractions.begin(), group_fractions.end());
  }
  progress.Finish();

  summary.num_images = hit_fractions.size();
  for (double fraction : hit_fractions) summary.mean_hit_fraction += fraction;
  if (!hit_fractions.empty()) summary.mean_hit_fraction /= static_cast<double>(hit_fractions.size());
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace lutex
