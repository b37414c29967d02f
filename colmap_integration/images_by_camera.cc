#include "colmap_integration/images_by_camera.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

GeometryMapsOptions PerImageMapsOptions() {
  GeometryMapsOptions options;
  options.num_threads = 1;
  return options;
}

void ForEachImageWithRays(const SparseModel& model, int num_threads, const std::string& progress_label,
                          const std::function<void(const Image&, const CameraRays&)>& visit) {
  ForEachImageWithRaysOnWorkers(model, num_threads, progress_label,
                                [&](const Image& image, const CameraRays& rays, int) { visit(image, rays); });
}

void ForEachImageWithRaysOnWorkers(const SparseModel& model, int num_threads, const std::string& progress_label,
                                   const std::function<void(const Image&, const CameraRays&, int worker)>& visit) {
  using CameraKey = std::tuple<int, std::uint64_t, std::uint64_t, std::vector<double>>;
  std::map<CameraKey, std::vector<const Image*>> images_by_camera;
  for (const auto& entry : model.images) {
    const Camera& camera = model.cameras.at(entry.second.camera_id);
    images_by_camera[CameraKey(static_cast<int>(camera.model_id), camera.width, camera.height, camera.params)]
        .push_back(&entry.second);
  }
  ProgressReporter progress(progress_label, model.images.size(), "images");
  for (const auto& [key, images] : images_by_camera) {
    const CameraRays rays(model.cameras.at(images.front()->camera_id), num_threads);
    ParallelForOnWorkers(images.size(), num_threads, [&](std::size_t i, int worker) {
      visit(*images[i], rays, worker);
      progress.Advance();
    });
  }
  progress.Finish();
}

SparseModel WithoutDoneImages(const SparseModel& model,
                              const std::function<std::vector<std::filesystem::path>(const Image&)>& outputs_of) {
  SparseModel todo;
  todo.cameras = model.cameras;
  for (const auto& [id, image] : model.images) {
    const std::vector<std::filesystem::path> outputs = outputs_of(image);
    const bool done = std::all_of(outputs.begin(), outputs.end(),
                                  [](const std::filesystem::path& path) { return std::filesystem::exists(path); });
    if (!done) todo.images.emplace(id, image);
  }
  return todo;
}

}  // namespace lutex
