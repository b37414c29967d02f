#pragma once

// Analytic meshes: the shapes tests know exact answers for, and the terrain of the bundled example.

#include <functional>

#include "lib/geometry/mesh.h"

namespace lutex {

// A regular grid over [x_min, x_max] x [y_min, y_max] with `cells_x` x `cells_y` cells (two triangles
// each), vertex heights z = height(x, y). Vertex texture coordinates span [0, 1]^2 (v = 0 at y_min).
Mesh MakeHeightFieldMesh(const std::function<double(double, double)>& height, double x_min, double x_max,
                         double y_min, double y_max, int cells_x, int cells_y);

// The 12 triangles of an axis-aligned box.
Mesh MakeBoxMesh(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner);

// A latitude-longitude sphere whose vertices lie exactly on the sphere.
Mesh MakeSphereMesh(const Eigen::Vector3d& centre, double radius, int num_latitudes, int num_longitudes);

// Appends `other` to `mesh` (indices shifted). Attributes are kept only if both meshes have them.
void AppendMesh(const Mesh& other, Mesh* mesh);

}  // namespace lutex
