#pragma once

// `lutex mesh`: a surface for a workspace that has only a sparse model (lib/geometry/sparse_surface.h: a
// regularised 2.5-D height field from the sparse points), for machines without the GPU COLMAP's dense
// stereo needs. Up is the georeferenced frame's +z when there is a georeference (workspace_georeference.h),
// else opposite the cameras' mean viewing direction (lib/geometry/up_direction.h), unless `up_axis` says.
// The points: a dense workspace's fused cloud (W/dense/N/fused.ply) when there is one, else the sparse
// model's. Output: default W/lutex/mesh/mesh.ply, in the model's frame.

#include <filesystem>
#include <ostream>
#include <string>

#include <Eigen/Core>

#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/workspace_georeference.h"
#include "lib/geometry/sparse_surface.h"

namespace lutex {

struct MeshOptions {
  std::filesystem::path workspace;
  std::filesystem::path output;  // empty: W/lutex/mesh/mesh.ply
  SparseSurfaceOptions surface;
  GeoreferenceOptions georeference;
  std::string up_axis = "auto";  // "x", "-x", ..., "-z", or auto (see above)
  void Check() const;
};

struct MeshSummary {
  std::filesystem::path output;
  SparseSurfaceSummary surface;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  std::string up_source;  // "given", "the georeferenced frame", "the cameras"
  std::filesystem::path points;  // the fused cloud used, or the sparse model's folder
  double seconds = 0.0;
};

MeshSummary MeshWorkspace(const MeshOptions& options);

// The mesh a dense COLMAP workspace made itself (W/dense/N/meshed-*.ply, the first found), or empty.
std::filesystem::path DenseMeshOf(const Workspace& workspace);

// The lines the stage prints when done.
void PrintMeshSummary(std::ostream& out, const MeshSummary& summary);

}  // namespace lutex
