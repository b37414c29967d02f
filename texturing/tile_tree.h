#pragma once

// The spatial tiles of a tiled bake (3D Tiles): a quadtree over the horizontal footprint of the mesh.
//
// Footprints are squares in the tiles frame (gltf_frame.h: +Z up, so x and y are horizontal). A tile is
// split into its four quadrants while it holds more than `max_faces` faces and is above `max_depth`;
// a face belongs to the leaf under its centroid. Empty quadrants are not kept. The tree is the same for
// any thread count and any face order of equal geometry.
//
// Made in passes over the faces that count them in the squares a few levels below each tile still to be
// split (at most 4 MiB of counters; deeper trees take more passes), then one that fills the leaves' lists:
// memory is those lists (4 bytes a face), not the faces' order or centroids.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lib/geometry/mesh.h"

namespace lutex {

struct TileNode {
  int depth = 0;                    // the root is 0
  std::string name;                 // "0", its children "0_0" to "0_3" (quadrant: 1 east, 2 north)
  Eigen::AlignedBox2d footprint;    // in the tiles frame's x, y
  std::vector<std::size_t> children;  // indices in TileTree::nodes
  std::vector<std::uint32_t> faces;   // leaves only: the mesh's faces, ascending
};

struct TileTree {
  // The root first; a parent before its children.
  std::vector<TileNode> nodes;
  std::size_t NumLeaves() const;
};

struct TileTreeOptions {
  std::size_t max_faces = 100000;  // per leaf, unless max_depth stops the split
  int max_depth = 12;
  void Check() const;
};

// Throws std::invalid_argument on bad options or a mesh without faces.
// `tiles_from_model`: the rotation of the mesh's frame to the tiles frame (TilesFromModel).
TileTree PartitionIntoTiles(const Mesh& mesh, const Eigen::Matrix3d& tiles_from_model, const TileTreeOptions& options);

}  // namespace lutex
