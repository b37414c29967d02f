#include "texturing/tile_mesh.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include <meshoptimizer.h>

namespace lutex {

namespace {

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

// The vertices `faces` use, in ascending order of index, with faces renumbered to them.
TileMesh Compact(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::uint32_t>& source_of_vertex,
                 const std::vector<Mesh::Face>& faces) {
  std::vector<std::uint32_t> new_index(vertices.size(), kUnused);
  for (const Mesh::Face& face : faces) {
    for (std::uint32_t v : face) new_index[v] = 0;
  }
  TileMesh tile;
  for (std::uint32_t v = 0; v < vertices.size(); ++v) {
    if (new_index[v] == kUnused) continue;
    new_index[v] = static_cast<std::uint32_t>(tile.mesh.vertices.size());
    tile.mesh.vertices.push_back(vertices[v]);
    tile.source_vertex.push_back(source_of_vertex.empty() ? v : source_of_vertex[v]);
  }
  tile.mesh.faces.reserve(faces.size());
  for (const Mesh::Face& face : faces) tile.mesh.faces.push_back({new_index[face[0]], new_index[face[1]], new_index[face[2]]});
  return tile;
}

}  // namespace

TileMesh ExtractTileMesh(const Mesh& mesh, const std::vector<std::uint32_t>& faces) {
  std::vector<Mesh::Face> chosen;
  chosen.reserve(faces.size());
  for (std::uint32_t f : faces) chosen.push_back(mesh.faces.at(f));
  return Compact(mesh.vertices, {}, chosen);
}

TileMesh MergeTileMeshes(const std::vector<const TileMesh*>& parts) {
  // Source index -> merged index, assigned in ascending source order.
  std::map<std::uint32_t, std::uint32_t> merged_index;
  for (const TileMesh* part : parts) {
    for (std::uint32_t source : part->source_vertex) merged_index.emplace(source, 0);
  }
  TileMesh merged;
  merged.mesh.vertices.resize(merged_index.size());
  merged.source_vertex.reserve(merged_index.size());
  for (auto& [source, index] : merged_index) {
    index = static_cast<std::uint32_t>(merged.source_vertex.size());
    merged.source_vertex.push_back(source);
  }
  for (const TileMesh* part : parts) {
    std::vector<std::uint32_t> index_of(part->source_vertex.size());
    for (std::size_t v = 0; v < part->source_vertex.size(); ++v) {
      index_of[v] = merged_index.at(part->source_vertex[v]);
      merged.mesh.vertices[index_of[v]] = part->mesh.vertices[v];
    }
    for (const Mesh::Face& face : part->mesh.faces) {
      merged.mesh.faces.push_back({index_of[face[0]], index_of[face[1]], index_of[face[2]]});
    }
  }
  return merged;
}

SimplifiedTileMesh SimplifyTileMesh(const TileMesh& tile, std::size_t target_faces) {
  if (target_faces == 0) throw std::invalid_argument("tiles: a simplified tile needs at least one face");
  SimplifiedTileMesh result;
  if (tile.mesh.faces.size() <= target_faces) {
    result.tile = tile;
    return result;
  }
  // meshoptimizer works in float: positions relative to their mean keep millimetres at any offset.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : tile.mesh.vertices) mean += v;
  mean /= double(tile.mesh.vertices.size());
  std::vector<float> positions;
  positions.reserve(3 * tile.mesh.vertices.size());
  for (const Eigen::Vector3d& v : tile.mesh.vertices) {
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(v[k] - mean[k]));
  }
  std::vector<unsigned int> indices;
  indices.reserve(3 * tile.mesh.faces.size());
  for (const Mesh::Face& face : tile.mesh.faces) indices.insert(indices.end(), face.begin(), face.end());
  std::vector<unsigned int> simplified(indices.size());
  float relative_error = 0.0f;
  // No error bound (1 = the mesh's extent): the face budget decides, and the error it cost is reported.
  const std::size_t count =
      meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions.data(), tile.mesh.vertices.size(),
                       3 * sizeof(float), 3 * target_faces, 1.0f, meshopt_SimplifyLockBorder, &relative_error);
  const float scale = meshopt_simplifyScale(positions.data(), tile.mesh.vertices.size(), 3 * sizeof(float));
  std::vector<Mesh::Face> faces;
  faces.reserve(count / 3);
  for (std::size_t i = 0; i + 2 < count; i += 3) faces.push_back({simplified[i], simplified[i + 1], simplified[i + 2]});
  result.tile = Compact(tile.mesh.vertices, tile.source_vertex, faces);
  result.error = double(relative_error) * double(scale);
  return result;
}

}  // namespace lutex
