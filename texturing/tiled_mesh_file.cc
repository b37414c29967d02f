#include "texturing/tiled_mesh_file.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "lib/util/binary_io.h"

namespace lutex {

namespace {

constexpr std::uint32_t kNotInTile = 0xffffffffu;

}  // namespace

TiledMeshFile::TiledMeshFile(const Mesh& mesh, const std::vector<const std::vector<std::uint32_t>*>& tiles,
                             const std::filesystem::path& scratch, std::uint32_t unset_label)
    : file_(scratch) {
  std::ofstream out(file_.temporary_path(), std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(file_.temporary_path().string() + ": cannot write the mesh's scratch file");
  std::vector<bool> seen(mesh.faces.size(), false);
  std::vector<std::uint32_t> index_in_tile(mesh.vertices.size(), kNotInTile);
  std::vector<std::uint32_t> vertices;
  std::vector<Eigen::Vector3d> positions;
  std::vector<Mesh::Face> corners;
  std::vector<std::uint32_t> labels;
  std::uint64_t offset = 0;
  for (const std::vector<std::uint32_t>* faces : tiles) {
    vertices.clear();
    if (!std::is_sorted(faces->begin(), faces->end())) {
      throw std::invalid_argument("tiled mesh: each tile's faces must be in ascending order");
    }
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
    labels.assign(faces->size(), unset_label);
    WriteBinaryArray(out, labels);
    offset += 4 * sizeof(std::uint64_t) + faces->size() * (sizeof(std::uint32_t) + sizeof(Mesh::Face)) +
              vertices.size() * (sizeof(std::uint32_t) + sizeof(Eigen::Vector3d));
    label_offsets_.push_back(offset);
    offset += sizeof(std::uint64_t) + labels.size() * sizeof(std::uint32_t);
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
    std::uint32_t label;
    std::array<std::uint32_t, 3> mesh_vertices;
  };
  std::vector<KeptFace> kept;
  std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> kept_vertices;  // (index in the mesh, position)
  std::vector<std::uint32_t> faces, vertices;
  std::vector<Eigen::Vector3d> positions;
  std::vector<Mesh::Face> corners;
  std::vector<std::uint32_t> labels;
  std::vector<bool> used;
  try {
    for (std::size_t t : tiles) {
      in.seekg(static_cast<std::streamoff>(offsets_.at(t)));
      ReadBinaryArray(in, "a tile's faces", faces);
      ReadBinaryArray(in, "a tile's vertices", vertices);
      ReadBinaryArray(in, "a tile's positions", positions);
      ReadBinaryArray(in, "a tile's corners", corners);
      ReadBinaryArray(in, "a tile's labels", labels);
      if (positions.size() != vertices.size() || corners.size() != faces.size() || labels.size() != faces.size()) {
        throw std::runtime_error("a tile's record does not add up");
      }
      used.assign(vertices.size(), false);
      for (std::size_t i = 0; i < faces.size(); ++i) {
        Eigen::AlignedBox3d face_box;
        for (std::uint32_t v : corners[i]) face_box.extend(positions.at(v));
        if (!keep(t, face_box)) continue;
        const Mesh::Face& c = corners[i];
        kept.push_back(
            {faces[i], static_cast<std::uint32_t>(t), labels[i], {vertices[c[0]], vertices[c[1]], vertices[c[2]]}});
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
  piece.label.reserve(kept.size());
  for (const KeptFace& face : kept) {
    tile_mesh.mesh.faces.push_back(
        {index_of(face.mesh_vertices[0]), index_of(face.mesh_vertices[1]), index_of(face.mesh_vertices[2])});
    piece.mesh_face.push_back(face.mesh_face);
    piece.tile.push_back(face.tile);
    piece.label.push_back(face.label);
  }
  return piece;
}

void TiledMeshFile::SetLabels(const std::vector<std::uint32_t>& mesh_faces, const std::vector<std::uint32_t>& tiles,
                              const std::vector<std::uint32_t>& labels) {
  if (tiles.size() != mesh_faces.size() || labels.size() != mesh_faces.size()) {
    throw std::invalid_argument("tiled mesh: one tile and one label per face to label");
  }
  std::vector<std::size_t> order(mesh_faces.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (tiles[i] >= num_tiles()) throw std::invalid_argument("tiled mesh: a face to label is in no tile");
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tiles[a] < tiles[b]; });
  const std::string& name = file_.temporary_path().string();
  std::fstream file(file_.temporary_path(), std::ios::binary | std::ios::in | std::ios::out);
  if (!file) throw std::runtime_error(name + ": cannot open the mesh's scratch file to label its faces");
  std::vector<std::uint32_t> faces, tile_labels;
  for (std::size_t begin = 0; begin < order.size();) {
    const std::uint32_t t = tiles[order[begin]];
    std::size_t end = begin;
    while (end < order.size() && tiles[order[end]] == t) ++end;
    try {
      file.seekg(static_cast<std::streamoff>(offsets_[t]));
      ReadBinaryArray(file, "a tile's faces", faces);
      file.seekg(static_cast<std::streamoff>(label_offsets_[t]));
      ReadBinaryArray(file, "a tile's labels", tile_labels);
    } catch (const std::runtime_error& error) {
      throw std::runtime_error(name + ": " + error.what() + " (the mesh's scratch file)");
    }
    if (tile_labels.size() != faces.size()) throw std::runtime_error(name + ": a tile's record does not add up");
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t face = mesh_faces[order[k]];
      const auto found = std::lower_bound(faces.begin(), faces.end(), face);
      if (found == faces.end() || *found != face) {
        throw std::invalid_argument("tiled mesh: face " + std::to_string(face) + " is not in tile " +
                                    std::to_string(t));
      }
      tile_labels[static_cast<std::size_t>(found - faces.begin())] = labels[order[k]];
    }
    file.seekp(static_cast<std::streamoff>(label_offsets_[t] + sizeof(std::uint64_t)));
    file.write(reinterpret_cast<const char*>(tile_labels.data()),
               static_cast<std::streamsize>(tile_labels.size() * sizeof(std::uint32_t)));
    if (!file) {
      throw std::runtime_error(name + ": could not label the faces in the mesh's scratch file (is the disk full?)");
    }
    begin = end;
  }
  file.flush();
  if (!file) {
    throw std::runtime_error(name + ": could not label the faces in the mesh's scratch file (is the disk full?)");
  }
}

}  // namespace lutex
