#pragma once

// The first hits of a few rays on a large mesh without a ray-casting index (raycast_scene.h builds one of
// about 100 bytes a face): one pass over the faces, each tested against the rays that cross its cell of a
// coarse grid over the mesh's horizontal extent (x, y). Memory is that of the rays and the grid, not of
// the mesh; the work is one pass over the faces plus a triangle test per face and nearby ray. For a mosaic's
// GSD from the image centres of a whole dive (colmap_integration/stages/mosaic_workspace.h), where an index
// of the whole mesh would be built for a few thousand rays.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lib/geometry/mesh.h"

namespace lutex {

struct Ray3d {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // need not be unit
};

// For each ray, the distance along it to its first hit of either side of a face, in units of its
// direction's length; +infinity when it hits nothing. Throws std::invalid_argument for a zero direction.
std::vector<double> FirstHitDistances(const Mesh& mesh, const std::vector<Ray3d>& rays);

}  // namespace lutex
