#pragma once

// The dive's mesh on disk, tile by tile, so that a tiled bake holds the piece of the mesh it works on, not
// the whole mesh (`lutex tiles`, `lutex mosaic`: tile_views.h).
//
// Written once from the mesh and its tiles (each face in one tile). Any set of tiles is then read back as
// the TileMesh that ExtractTileMesh cuts from the mesh (tile_mesh.h): the faces kept in ascending order of
// their index in the mesh, their vertices in ascending order of theirs, positions bit for bit. So a piece
// read from the file is the piece cut from the mesh, and what is made from it does not change.
// Each face also carries a label on disk (a tiled bake: the view it was chosen from), `unset_label` until
// SetLabels writes it and read back with the piece: so what is kept of the dive between tiles is on disk,
// not 4 bytes a face in memory.
// In memory: each tile's box and where its record and its labels start.
//
// The file is scratch, read only by the process that writes it, in the machine's byte order. Per tile, in
// the tiles' order, each array after its count (binary_io.h WriteBinaryArray): the tile's faces' indices in
// the mesh (uint32, ascending); its vertices' indices in the mesh (uint32, ascending); their positions
// (3 doubles each); its faces' corners (3 uint32 each, indices among the tile's vertices); its faces'
// labels (uint32, in the order of its faces), rewritten in place by SetLabels. About 34 bytes a face. It is
// written under a temporary name (atomic_output.h), never committed: the destructor removes it, and a
// killed process's is a stale temporary that `lutex run` cleans.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "lib/geometry/mesh.h"
#include "lib/util/atomic_output.h"
#include "texturing/tile_mesh.h"

namespace lutex {

class TiledMeshFile {
 public:
  // Writes `mesh` tile by tile (`tiles`: each tile's faces, ascending) beside `scratch` under a temporary
  // name, every face labelled `unset_label`. Throws std::invalid_argument when a tile's faces are not
  // ascending, a tile's face is not in the mesh or the tiles do not hold each face once, std::runtime_error
  // naming the file when it cannot be written.
  TiledMeshFile(const Mesh& mesh, const std::vector<const std::vector<std::uint32_t>*>& tiles,
                const std::filesystem::path& scratch, std::uint32_t unset_label = 0xffffffffu);
  TiledMeshFile(const TiledMeshFile&) = delete;
  TiledMeshFile& operator=(const TiledMeshFile&) = delete;

  std::size_t num_tiles() const { return boxes_.size(); }
  std::size_t num_faces() const { return num_faces_; }  // the mesh's
  // Of the tile's faces (empty for a tile without faces).
  const Eigen::AlignedBox3d& box(std::size_t tile) const { return boxes_.at(tile); }

  struct Piece {
    TileMesh tile_mesh;
    std::vector<std::uint32_t> mesh_face;  // per face of tile_mesh, its index in the mesh (ascending)
    std::vector<std::uint32_t> tile;       // per face of tile_mesh, the tile it is in
    std::vector<std::uint32_t> label;      // per face of tile_mesh, its label
  };
  // The faces of `tiles` for which `keep(tile, the face's box)` is true. Throws std::runtime_error naming
  // the file when it cannot be read back.
  Piece Read(const std::vector<std::size_t>& tiles,
             const std::function<bool(std::size_t tile, const Eigen::AlignedBox3d& face_box)>& keep) const;

  // Labels the faces `mesh_faces` (indices in the mesh; `tiles`: the tile each is in, as a Piece gives it)
  // with `labels`, one each (a face given twice gets the later label), each tile's labels read and rewritten
  // at once. Throws std::invalid_argument when the three differ in length or a face is not in the tile given
  // for it (the tiles before it in order of index keep their new labels), std::runtime_error naming the
  // file when it cannot be read or written.
  void SetLabels(const std::vector<std::uint32_t>& mesh_faces, const std::vector<std::uint32_t>& tiles,
                 const std::vector<std::uint32_t>& labels);

 private:
  AtomicOutputFile file_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  std::vector<std::uint64_t> offsets_;        // of each tile's record
  std::vector<std::uint64_t> label_offsets_;  // of each tile's labels (their count before them)
  std::size_t num_faces_ = 0;
};

}  // namespace lutex
