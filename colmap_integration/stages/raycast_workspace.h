#pragma once

// `lutex raycast`: per-image depth and normal maps of a mesh seen by every registered image of a COLMAP
// workspace.
//
// Output, under `output` (default W/lutex/raycast):
//   depth_maps/NAME.geometric.bin   planar depth z, COLMAP array format, 0 where nothing is hit
//   normal_maps/NAME.geometric.bin  unit normals in the camera frame facing the camera, 0 where no hit
//   previews/NAME.depth.png, previews/NAME.normal.png   8-bit pictures
// "geometric" is the slot COLMAP's stereo_fusion reads, so `output` may be a dense workspace's stereo/.

#include <cstddef>
#include <filesystem>
#include <ostream>

#include "colmap_integration/stages/loaded_dive.h"

namespace lutex {

struct RaycastOptions {
  // COLMAP workspace (images/, sparse/0 or sparse/).
  std::filesystem::path workspace;
  // Mesh in the same world frame as the sparse model (.ply, .obj, .off, .stl).
  std::filesystem::path mesh;
  // Output folder; empty means W/lutex/raycast.
  std::filesystem::path output;
  // Threads over images; <= 0 uses all cores. Results do not depend on it.
  int num_threads = 0;
  // The stage refuses to start when its memory estimate (stage_memory.h) exceeds this; 0: the machine's
  // available memory.
  std::size_t memory_limit_bytes = 0;
  // Also write 8-bit previews.
  bool write_previews = true;
  // Leave images alone whose outputs all exist (lutex run resumes so: every file is written under a
  // temporary name and renamed when complete, so an existing one is whole).
  bool skip_done = false;

  // Throws std::invalid_argument with the reason when an option is missing or nonsense.
  void Check() const;
};

struct RaycastSummary {
  std::filesystem::path output;
  std::size_t num_images = 0;   // ray-cast now
  std::size_t num_skipped = 0;  // already done (skip_done)
  std::size_t num_faces = 0;
  double mean_hit_fraction = 0.0;  // fraction of pixels that see the mesh, averaged over the images ray-cast now
  bool wrote_previews = false;
  double seconds = 0.0;
};

// Reads everything and validates it before writing anything.
RaycastSummary RaycastWorkspace(const RaycastOptions& options);
// The same on a dive loaded before (`lutex run` loads it once for every stage): `dive` holds the workspace
// and mesh of `options`.
RaycastSummary RaycastWorkspace(const RaycastOptions& options, const LoadedDive& dive);

// The lines the stage prints when done.
void PrintRaycastSummary(std::ostream& out, const RaycastSummary& summary);

}  // namespace lutex
