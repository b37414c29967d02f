#pragma once

// A triangle mesh in the world frame. Vertices are double precision because survey meshes are often
// georeferenced (coordinates of 10^5-10^6 m, where float has ~0.1 m resolution); consumers that need
// float (Embree) subtract a local origin first.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lutex {

struct Mesh {
  using Face = std::array<std::uint32_t, 3>;

  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  // Optional attributes: empty, or one entry per vertex (colours as stored: 8-bit, usually sRGB).
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> vertex_colors;
  std::vector<Eigen::Vector2f> vertex_texcoords;
  // Shading normals (unit), for smooth shading between faces.
  std::vector<Eigen::Vector3f> vertex_normals;
  // Optional per-face colours (8-bit, usually sRGB), empty or one per face.
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> face_colors;
  // Optional per-face-corner texture coordinates (OBJ-style), empty or 3 per face.
  std::vector<std::array<Eigen::Vector2f, 3>> corner_texcoords;

  std::size_t NumVertices() const { return vertices.size(); }
  std::size_t NumFaces() const { return faces.size(); }

  // Throws std::runtime_error starting with `context` when the mesh has no faces, a vertex that is not
  // finite, a face index out of range, or attribute arrays of the wrong length.
  void Check(const std::string& context) const;

  // Removes faces with a repeated vertex index or zero area; returns how many were removed.
  std::size_t RemoveDegenerateFaces();

  // Axis-aligned bounds; (inf, -inf) for an empty mesh.
  Eigen::Vector3d BoundsMin() const;
  Eigen::Vector3d BoundsMax() const;
};

}  // namespace lutex
