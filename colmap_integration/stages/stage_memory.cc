#include "colmap_integration/stages/stage_memory.h"

#include <algorithm>

#include "lib/util/parallel_for.h"

namespace lutex {

namespace {

// Embree's triangle BVH at high build quality holds about this much per triangle (its nodes and
// pre-gathered triangle blocks), on top of the float vertex and index buffers lutex hands it.
constexpr double kBvhBytesPerFace = 64.0;
// A ray table holds one float direction per pixel (camera_rays.h).
constexpr double kRayTableBytesPerPixel = 12.0;

}  // namespace

MemoryEstimate FusionBudget(const TexelFusionOptions& fusion) {
  MemoryEstimate estimate;
  estimate.Add("the texel fusion's budget", 1.0, static_cast<double>(fusion.memory_limit_bytes));
  return estimate;
}

void CheckStageMemory(const std::string& stage, const LoadedDive& dive, int num_threads, double bytes_per_pixel,
                      std::size_t limit_bytes, MemoryEstimate extra) {
  const Mesh& mesh = dive.mesh();
  extra.Add("the mesh and its ray-casting index", 1.0,
            static_cast<double>(mesh.vertices.size()) * (sizeof(Eigen::Vector3d) + sizeof(Eigen::Vector3f) + 12.0) +
                static_cast<double>(mesh.faces.size()) * (sizeof(Mesh::Face) + 12.0 + kBvhBytesPerFace));
  double largest_pixels = 0.0;
  for (const auto& [id, camera] : dive.model().cameras) {
    largest_pixels = std::max(largest_pixels, static_cast<double>(camera.width) * static_cast<double>(camera.height));
  }
  const int workers = ResolveNumThreads(num_threads);
  // Cameras are visited one group at a time (images_by_camera.h): one table is held at a time.
  extra.Add("the ray table of a camera", largest_pixels, kRayTableBytesPerPixel);
  extra.Add(std::to_string(workers) + " workers' image buffers", static_cast<double>(workers) * largest_pixels,
            bytes_per_pixel);
  CheckMemoryEstimate(dive.workspace().root.string() + ": " + stage, extra, limit_bytes);
}

}  // namespace lutex
