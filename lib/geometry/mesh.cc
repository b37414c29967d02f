#include "lib/geometry/mesh.h"

#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

namespace lutex {

void Mesh::Check(const std::string& context) const {
  if (faces.empty()) throw std::runtime_error(context + ": the mesh has no faces");
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      throw std::runtime_error(context + ": vertex " + std::to_string(i) + " is not finite (NaN or inf)");
    }
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::uint32_t index : faces[f]) {
      if (index >= vertices.size()) {
        throw std::runtime_error(context + ": face " + std::to_string(f) + " names vertex " +
                                 std::to_string(index) + " but the mesh has " +
                                 std::to_string(vertices.size()) + " vertices");
      }
    }
  }
  if (!vertex_colors.empty() && vertex_colors.size() != vertices.size()) {
    throw std::runtime_error(context + ": vertex colour count differs from vertex count");
  }
  if (!vertex_texcoords.empty() && vertex_texcoords.size() != vertices.size()) {
    throw std::runtime_error(context + ": texture coordinate count differs from vertex count");
  }
  if (!vertex_normals.empty() && vertex_normals.size() != vertices.size()) {
    throw std::runtime_error(context + ": vertex normal count differs from vertex count");
  }
  if (!face_colors.empty() && face_colors.size() != faces.size()) {
    throw std::runtime_error(context + ": face colour count differs from face count");
  }
  if (!corner_texcoords.empty() && corner_texcoords.size() != faces.size()) {
    throw std::runtime_error(context + ": per-corner texture coordinate count differs from face count");
  }
}

std::size_t Mesh::RemoveDegenerateFaces() {
  std::size_t kept = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Face& face = faces[f];
    const bool repeated = face[0] == face[1] || face[1] == face[2] || face[0] == face[2];
    const bool zero_area =
        !repeated && (vertices[face[1]] - vertices[face[0]]).cross(vertices[face[2]] - vertices[face[0]])
                             .squaredNorm() == 0.0;
    if (repeated || zero_area) continue;
    faces[kept] = face;
    if (!corner_texcoords.empty()) corner_texcoords[kept] = corner_texcoords[f];
    if (!face_colors.empty()) face_colors[kept] = face_colors[f];
    ++kept;
  }
  const std::size_t removed = faces.size() - kept;
  faces.resize(kept);
  if (!corner_texcoords.empty()) corner_texcoords.resize(kept);
  if (!face_colors.empty()) face_colors.resize(kept);
  return removed;
}

Eigen::Vector3d Mesh::BoundsMin() const {
  Eigen::Vector3d result = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) result = result.cwiseMin(v);
  return result;
}

Eigen::Vector3d Mesh::BoundsMax() const {
  Eigen::Vector3d result = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) result = result.cwiseMax(v);
  return result;
}

}  // namespace lutex
