#pragma once

// The sparse 3-D points a structure-from-motion run would give for a simulated survey, as COLMAP stores
// them: surface points, each with the images that see it (track), its 2-D observation in each and a
// reprojection error. Lets `lutex mesh` and its tests and benchmarks run on simulated dives, with the true
// surface to compare against.
//
// Each image contributes points at a regular grid of `points_per_image` pixels (ray cast onto the mesh);
// a point's track is every image it projects into, unoccluded (a ray from that camera reaches it first) and
// seen at most 80 degrees from its face's normal. Points seen by fewer than 2 images are dropped, as SfM
// drops them. Positions get Gaussian noise of `noise` model units; the error field is that noise in
// pixels at the first image's range. Deterministic for a seed; independent of the thread count.

#include <cstdint>
#include <vector>

#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"
#include "lib/geometry/sparse_model.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

struct SparsePointsOptions {
  int points_per_image = 0;  // 0: none
  double noise = 0.0;        // model units, per coordinate
  std::uint64_t seed = 1;
  int num_threads = 0;
};

// Adds the points to `model` (its images and camera must be set: the simulated poses) and fills the images'
// points2D. Returns how many points were added.
std::size_t AddSimulatedSparsePoints(const RaycastScene& scene, const SparsePointsOptions& options, SparseModel* model);

}  // namespace lutex
