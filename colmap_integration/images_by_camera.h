#pragma once

// Visits every registered image of a sparse model, in parallel, with the ray table of its camera.
// Images are grouped by camera (cameras with identical model, size and parameters share one group), and
// one ray table is built per group, so memory holds one table and `num_threads` images at a time,
// whatever the number of images. Progress is reported per image.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "colmap_integration/sparse_model.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

// Options for the maps of one visited image: depth and normals, on one thread (images already run in
// parallel).
GeometryMapsOptions PerImageMapsOptions();

// Calls visit(image, rays) for every image; throws the first exception any call throws.
void ForEachImageWithRays(const SparseModel& model, int num_threads, const std::string& progress_label,
                          const std::function<void(const Image&, const CameraRays&)>& visit);

// The same, also telling visit which worker runs it (0 <= worker < ResolveNumThreads(num_threads)), for
// buffers kept per worker and reused from image to image.
void ForEachImageWithRaysOnWorkers(const SparseModel& model, int num_threads, const std::string& progress_label,
                                   const std::function<void(const Image&, const CameraRays&, int worker)>& visit);

// The cameras of `model` and those of its images that still have an output to write: an image is done when
// every file `outputs_of(image)` names exists (files are written under temporary names and renamed, so an
// existing one is complete). No 3-D points. Resumed runs visit this instead of the whole model.
SparseModel WithoutDoneImages(const SparseModel& model,
                              const std::function<std::vector<std::filesystem::path>(const Image&)>& outputs_of);

}  // namespace lutex
