#include "lib/geometry/mesh_primitives.h"

#include <cmath>

namespace lutex {

Mesh MakeHeightFieldMesh(const std::function<double(double, double)>& height, double x_min, double x_max,
                         double y_min, double y_max, int cells_x, int cells_y) {
  Mesh mesh;
  for (int j = 0; j <= cells_y; ++j) {
    for (int i = 0; i <= cells_x; ++i) {
      const double s = static_cast<double>(i) / cells_x, t = static_cast<double>(j) / cells_y;
      const double x = x_min + s * (x_max - x_min), y = y_min + t * (y_max - y_min);
      mesh.vertices.emplace_back(x, y, height(x, y));
      mesh.vertex_texcoords.emplace_back(static_cast<float>(s), static_cast<float>(t));
    }
  }
  const auto index = [cells_x](int i, int j) { return static_cast<std::uint32_t>(j * (cells_x + 1) + i); };
  for (int j = 0; j < cells_y; ++j) {
    for (int i = 0; i < cells_x; ++i) {
      mesh.faces.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      mesh.faces.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  return mesh;
}

Mesh MakeBoxMesh(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner) {
  Mesh mesh;
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back((k & 1) ? max_corner.x() : min_corner.x(), (k & 2) ? max_corner.y() : min_corner.y(),
                               (k & 4) ? max_corner.z() : min_corner.z());
  }
  // Two triangles per side, wound counter-clockwise seen from outside.
  mesh.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return mesh;
}

Mesh MakeSphereMesh(const Eigen::Vector3d& centre, double radius, int num_latitudes, int num_longitudes) {
  Mesh mesh;
  mesh.vertices.push_back(centre + Eigen::Vector3d(0, 0, radius));
  for (int lat = 1; lat < num_latitudes; ++lat) {
    const double polar = M_PI * lat / num_latitudes;
    for (int lon = 0; lon < num_longitudes; ++lon) {
      const double azimuth = 2.0 * M_PI * lon / num_longitudes;
      mesh.vertices.push_back(centre + radius * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth),
                                                                std::sin(polar) * std::sin(azimuth), std::cos(polar)));
    }
  }
  mesh.vertices.push_back(centre - Eigen::Vector3d(0, 0, radius));
  const auto ring = [num_longitudes](int lat, int lon) {
    return static_cast<std::uint32_t>(1 + (lat - 1) * num_longitudes + (lon % num_longitudes));
  };
  const auto south = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  for (int lon = 0; lon < num_longitudes; ++lon) {
    mesh.faces.push_back({0, ring(1, lon), ring(1, lon + 1)});
    for (int lat = 1; lat + 1 < num_latitudes; ++lat) {
      mesh.faces.push_back({ring(lat, lon), ring(lat + 1, lon), ring(lat + 1, lon + 1)});
      mesh.faces.push_back({ring(lat, lon), ring(lat + 1, lon + 1), ring(lat, lon + 1)});
    }
    mesh.faces.push_back({ring(num_latitudes - 1, lon), south, ring(num_latitudes - 1, lon + 1)});
  }
  return mesh;
}

void AppendMesh(const Mesh& other, Mesh* mesh) {
  const auto offset = static_cast<std::uint32_t>(mesh->vertices.size());
  const bool colors = !mesh->vertex_colors.empty() && !other.vertex_colors.empty();
  const bool texcoords = !mesh->vertex_texcoords.empty() && !other.vertex_texcoords.empty();
  const bool normals = !mesh->vertex_normals.empty() && !other.vertex_normals.empty();
  mesh->vertices.insert(mesh->vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const Mesh::Face& face : other.faces) mesh->faces.push_back({face[0] + offset, face[1] + offset, face[2] + offset});
  if (colors) {
    mesh->vertex_colors.insert(mesh->vertex_colors.end(), other.vertex_colors.begin(), other.vertex_colors.end());
  } else {
    mesh->vertex_colors.clear();
  }
  if (texcoords) {
    mesh->vertex_texcoords.insert(mesh->vertex_texcoords.end(), other.vertex_texcoords.begin(),
                                  other.vertex_texcoords.end());
  } else {
    mesh->vertex_texcoords.clear();
  }
  if (normals) {
    mesh->vertex_normals.insert(mesh->vertex_normals.end(), other.vertex_normals.begin(), other.vertex_normals.end());
  } else {
    mesh->vertex_normals.clear();
  }
  mesh->corner_texcoords.clear();
}

}  // namespace lutex
