#include "texturing/tiled_mesh_file.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "lib/util/binary_io.h"

namespace lutex {

namespace {

constexpr std::uint32_t kNotInTile = 0xffffffffu;

}  // namespace

TiledMeshFile::TiledMeshFile(const Mesh& mesh, const std::vector<const std::vector<std::uint32_t>*>& tiles,
                             const std::filesystem::path& scratch)
    : file_(scratch) {
  std::ofstream out(file_.temporary_path(), std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(file_.temporary_path().string() + ": cannot write the mesh's scratch file");
  std::vector<bool> seen(mesh.faces.size(), false);
  std::vector<std::uint32_t> index_in_tile(mesh.vertices.size(), kNotInTile);
  std::vector<std::uint32_t> vertices;
  std::vector<Eigen::Vector3d> positions;
  std::vector<Mesh::Face> corners;
  std::uint64_t offset = 0;
  for (const std::vector<std::uint32_t>* faces : tiles) {
    vertices.clear();
    for (std::uint32_t f : *faces) {
      if (f >= mesh.faces.size() || seen[f]) {
        throw std::invalid_argument("tiled mesh: the tiles must hold each face of the mesh once");
      }
      seen[f] = true;
      vertices.insert(vertices.end(), mesh.faces[f].begin(), mesh.faces[f].end());
    }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    positions.clear();
    Eigen::AlignedBox3d box;
    for (std::uint32_t v = 0; v < vertices.size(); ++v) {
      index_in_tile[vertices[v]] = v;
      positions.push_back(mesh.vertices[vertices[v]]);
      box.extend(positions.back());
    }
    corners.clear();
    for (std::uint32_t f : *faces) {
      const Mesh::Face& face = mesh.faces[f];
      corners.push_back({index_in_tile[face[0]], index_in_tile[face[1]], index_in_tile[face[2]]});
    }
    for (std::uint32_t v : vertices) index_in_tile[v] = kNotInTile;
    offsets_.push_back(offset);
    boxes_.push_back(box);
    num_faces_ += faces->size();
    WriteBinaryArray(out, *faces);
    WriteBinaryArray(out, vertices);
    WriteBinaryArray(out, positions);
    WriteBinaryArray(out, corners);
    offset += 4 * sizeof(std::uint64_t) + faces->size() * (sizeof(std::uint32_t) + sizeof(Mesh::Face)) +
              vertices.size() * (sizeof(std::uint32_t) + sizeof(Eigen::Vector3d));
  }
  if (num_faces_ != mesh.faces.size()) {
    throw std::invalid_argument("tiled mesh: the tiles must hold each face of the mesh once");
  }
  out.flush();
  if (!out) {
    throw std::runtime_error(file_.temporary_path().string() + ": could not write the mesh's scratch file (is the disk full?)");
  }
}

TiledMeshFile::Piece TiledMeshFile::Read(
    const std::vector<std::size_t>& tiles,
    const std::function<bool(std::size_t tile, const Eigen::AlignedBox3d& face_box)>& keep) const {
  std::ifstream in(file_.temporary_path(), std::ios::binary);
  if (!in) throw std::runtime_error(file_.temporary_path().string() + ": cannot read the mesh's scratch file");
  struct KeptFace {
    std::uint32_t mesh_face;
    std::uint32_t tile;
    std::array<std::uint32_t, 3> mesh_vertices;
  };
  std::vector<KeptFace> kept;
  std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> kept_vertices;  // (index in the mesh, position)
  std::vector<std::uint32_t> faces, vertices;
  std::vector<Eigen::Vector3d> positions;
  std::vector<Mesh::Face> corners;
  std::vector<bool> used;
  try {
    for (std::size_t t : tiles) {
      in.seekg(static_cast<std::streamoff>(offsets_.at(t)));
      ReadBinaryArray(in, "a tile's faces", faces);
      ReadBinaryArray(in, "a tile's vertices", vertices);
      ReadBinaryArray(in, "a tile's positions", positions);
      ReadBinaryArray(in, "a tile's corners", corners);
      if (positions.size() != vertices.size() || corners.size() != faces.size()) {
        throw std::runtime_error("a tile's record does not add up");
      }
      used.assign(vertices.size(), false);
      for (std::size_t i = 0; i < faces.size(); ++i) {
        Eigen::AlignedBox3d face_box;
        for (std::uint32_t v : corners[i]) face_box.extend(positions.at(v));
        if (!keep(t, face_box)) continue;
        const Mesh::Face& c = corners[i];
        kept.push_back({faces[i], static_cast<std::uint32_t>(t), {vertices[c[0]], vertices[c[1]], vertices[c[2]]}});
        for (std::uint32_t v : c) used[v] = true;
      }
      for (std::size_t v = 0; v < vertices.size(); ++v) {
        if (used[v]) kept_vertices.emplace_back(vertices[v], positions[v]);
      }
    }
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(file_.temporary_path().string() + ": " + error.what() + " (the mesh's scratch file)");
  }
  std::sort(kept.begin(), kept.end(), [](const KeptFace& a, const KeptFace& b) { return a.mesh_face < b.mesh_face; });
  // A vertex on a border between tiles comes from each of them, with the same position.
  std::sort(kept_vertices.begin(), kept_vertices.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  kept_vertices.erase(std::unique(kept_vertices.begin(), kept_vertices.end(),
                                  [](const auto& a, const auto& b) { return a.first == b.first; }),
                      kept_vertices.end());
  Piece piece;
  TileMesh& tile_mesh = piece.tile_mesh;
  tile_mesh.mesh.vertices.reserve(kept_vertices.size());
  tile_mesh.source_vertex.reserve(kept_vertices.size());
  for (const auto& [index, position] : kept_vertices) {
    tile_mesh.source_vertex.push_back(index);
    tile_mesh.mesh.vertices.push_back(position);
  }
  const std::vector<std::uint32_t>& source = tile_mesh.source_vertex;
  const auto index_of = [&](std::uint32_t mesh_vertex) {
    return static_cast<std::uint32_t>(std::lower_bound(source.begin(), source.end(), mesh_vertex) - source.begin());
  };
  tile_mesh.mesh.faces.reserve(kept.size());
  piece.mesh_face.reserve(kept.size());
  piece.tile.reserve(kept.size());
  for (const KeptFace& face : kept) {
    tile_mesh.mesh.faces.push_back(
        {index_of(face.mesh_vertices[0]), index_of(face.mesh_vertices[1]), index_of(face.mesh_vertices[2])});
    piece.mesh_face.push_back(face.mesh_face);
    piece.tile.push_back(face.tile);
  }
  return piece;
}

}  // namespace lutex
