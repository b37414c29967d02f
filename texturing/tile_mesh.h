#pragma once

// The geometry of one tile of a tiled bake, and how a coarser level is made from its children.
//
// Every vertex of a tile's mesh is a vertex of the dive's mesh (`source_vertex` says which), at every
// level: leaves take the dive's faces, a parent merges its children's meshes (welding the vertices they
// share) and simplifies them by edge collapse onto existing vertices (meshoptimizer's meshopt_simplify).
// The open border of a tile is locked during simplification, so neighbouring tiles of one level keep
// meeting edge to edge: no cracks between tiles.

#include <cstdint>
#include <vector>

#include "lib/geometry/mesh.h"

namespace lutex {

struct TileMesh {
  Mesh mesh;
  std::vector<std::uint32_t> source_vertex;  // per vertex of `mesh`, ascending
};

// `faces` (ascending) of `mesh`, with the vertices they use in ascending order.
TileMesh ExtractTileMesh(const Mesh& mesh, const std::vector<std::uint32_t>& faces);

// The union of `parts`, vertices shared by their source index; faces in the parts' order.
TileMesh MergeTileMeshes(const std::vector<const TileMesh*>& parts);

struct SimplifiedTileMesh {
  TileMesh tile;
  // How far the simplified surface may lie from the one it was made from, in the mesh's units (meshopt's
  // relative error times the mesh's extent).
  double error = 0.0;
};

// At most `target_faces` faces where the locked border allows; a mesh already within it is returned as it
// is, with error 0. Throws std::invalid_argument when target_faces is 0.
SimplifiedTileMesh SimplifyTileMesh(const TileMesh& tile, std::size_t target_faces);

}  // namespace lutex
