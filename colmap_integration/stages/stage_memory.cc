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

MemoryEstimate TextureBakingMemory(const TextureBakingOptions& baking, std::size_t num_faces) {
  // Per face, with L views kept per face (face_view_candidates.h) and 3 neighbours (face_adjacency.h):
  //   candidates L x 8 + 1; the chosen view 4; neighbours 3 x 4 + 8; chart face id and corner texels
  //   4 + 3 x 8; texel range 16 (texel_layout.h). Per face of a view selection region
  //   (view_selection.h): data costs 4 L + 8, messages 3 x (4 L + 8), neighbours 3 x 4 + 8, labels and
  //   face ids 12.
  const double views = baking.visibility.max_views_per_face;
  const double per_face = (8.0 * views + 1.0) + 4.0 + 20.0 + 28.0 + 16.0;
  const double per_region_face = 4.0 * (4.0 * views + 8.0) + 20.0 + 12.0;
  // Seam levelling (seam_levelling_system.h), per face: at most one (vertex, view) correction (0.5 a face
  // on the tiles benchmark's survey), each with its solve's six vectors of 3 doubles, its value and view
  // (16) and about three chart edges of 9 bytes; and the face's three edges while they are gathered (24).
  const double per_face_levelling = baking.levelling.enabled ? 6.0 * 24.0 + 16.0 + 27.0 + 24.0 : 0.0;
  MemoryEstimate estimate;
  estimate.Add("the faces' view and chart tables", static_cast<double>(num_faces), per_face);
  estimate.Add("the view selection of a region", static_cast<double>(std::min(num_faces, baking.selection.max_region_faces)),
               per_region_face);
  if (per_face_levelling > 0.0) estimate.Add("the seam levelling", static_cast<double>(num_faces), per_face_levelling);
  estimate.Add("the texel fusion's budget", 1.0, static_cast<double>(baking.fusion.memory_limit_bytes));
  return estimate;
}

void CheckStageMemory(const std::string& stage, const LoadedDive& dive, int num_threads, double bytes_per_pixel,
                      std::size_t limit_bytes, MemoryEstimate extra, std::size_t indexed_faces) {
  const Mesh& mesh = dive.mesh();
  const double faces = static_cast<double>(mesh.faces.size());
  const double indexed = indexed_faces == 0 ? faces : std::min(faces, static_cast<double>(indexed_faces));
  // The index copies the vertices (as floats, and as doubles relative to its origin) with its faces.
  const double vertices_per_face = faces > 0.0 ? static_cast<double>(mesh.vertices.size()) / faces : 0.0;
  extra.Add("the mesh and its ray-casting index", 1.0,
            static_cast<double>(mesh.vertices.size()) * sizeof(Eigen::Vector3d) + faces * sizeof(Mesh::Face) +
                indexed * (vertices_per_face * (sizeof(Eigen::Vector3f) + 12.0) + 12.0 + kBvhBytesPerFace));
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
