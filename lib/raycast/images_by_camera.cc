#include "lib/raycast/images_by_camera.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

void ForEachImageWithMaps(
    const SparseModel& model, const RaycastScene& scene, int num_threads, const std::string& progress_label,
    const std::function<void(const Image&, const CameraRays&, const GeometryMaps&, int worker)>& visit) {
  using CameraKey = std::tuple<int, std::uint64_t, std::uint64_t, std::vector<double>>;
  std::map<CameraKey, std::vector<const Image*>> images_by_camera;
  for (const auto& entry : model.images) {
    const Camera& camera = model.cameras.at(entry.second.camera_id);
    images_by_camera[CameraKey(static_cast<int>(camera.model_id), camera.width, camera.height, camera.params)]
        .push_back(&entry.second);
  }
  // Depth and normals of one image on one thread (images already run in parallel).
  GeometryMapsOptions maps_options;
  maps_options.num_threads = 1;
  // The maps of the image each worker is on, reused from image to image.
  std::vector<GeometryMaps> worker_maps(static_cast<std::size_t>(ResolveNumThreads(num_threads)));
  ProgressReporter progress(progress_label, model.images.size(), "images");
  for (const auto& key_and_images : images_by_camera) {
    const auto& images = key_and_images.second;  // a lambda cannot capture a structured binding before C++20
    const CameraRays rays(model.cameras.at(images.front()->camera_id), num_threads);
    ParallelForOnWorkers(images.size(), num_threads, [&](std::size_t i, int worker) {
      GeometryMaps& maps = worker_maps[static_cast<std::size_t>(worker)];
      scene.Render(rays, images[i]->cam_from_world, maps_options, &maps);
      visit(*images[i], rays, maps, worker);
      progress.Advance();
    });
  }
  progress.Finish();
}

SparseModel OnlyImages(const SparseModel& model, const std::function<bool(const Image&)>& keep) {
  SparseModel kept;
  kept.cameras = model.cameras;
  for (const auto& [id, image] : model.images) {
    if (keep(image)) kept.images.emplace(id, image);
  }
  return kept;
}

SparseModel WithoutDoneImages(const SparseModel& model,
                              const std::function<std::vector<std::filesystem::path>(const Image&)>& outputs_of) {
  return OnlyImages(model, [&](const Image& image) {
    const std::vector<std::filesystem::path> outputs = outputs_of(image);
    return !std::all_of(outputs.begin(), outputs.end(),
                        [](const std::filesystem::path& path) { return std::filesystem::exists(path); });
  });
}

}  // namespace lutex
