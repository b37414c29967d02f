#pragma once

// Visits every registered image of a sparse model, in parallel, with the ray table of its camera and
// the image's ray-cast maps. Images are grouped by camera (cameras with identical model, size and
// parameters share one group), and one ray table is built per group; each worker casts its images into
// the same maps, so memory holds one table and `num_threads` images' maps at a time, whatever the number
// of images, and no fresh memory is taken per image. Progress is reported per image.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lib/geometry/sparse_model.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

// Calls visit(image, rays, maps, worker) for every image, `maps` being its depth, normals and face ids
// from `scene` and `worker` (0 <= worker < ResolveNumThreads(num_threads)) the worker running it, for
// the caller's own per-worker buffers. Throws the first exception any call throws.
void ForEachImageWithMaps(
    const SparseModel& model, const RaycastScene& scene, int num_threads, const std::string& progress_label,
    const std::function<void(const Image&, const CameraRays&, const GeometryMaps&, int worker)>& visit);

// The cameras of `model` and those of its images `keep` accepts. No 3-D points.
SparseModel OnlyImages(const SparseModel& model, const std::function<bool(const Image&)>& keep);

// The cameras of `model` and those of its images that still have an output to write: an image is done when
// every file `outputs_of(image)` names exists (files are written under temporary names and renamed, so an
// existing one is complete). No 3-D points. Resumed runs visit this instead of the whole model.
SparseModel WithoutDoneImages(const SparseModel& model,
                              const std::function<std::vector<std::filesystem::path>(const Image&)>& outputs_of);

}  // namespace lutex
