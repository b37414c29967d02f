#pragma once

// What a parent tile of a tiled bake is made from (tiles_workspace.h), held on disk while it waits.
//
// Tiles are baked bottom-up, depth first: a finished tile waits for its siblings before their parent is
// made from them, and a level deeper in the tree adds up to three more waiting tiles. Held in memory, each
// is its geometry, its texture at half resolution and a view per face, about 11 MB for a leaf of 80 k faces
// and 1100 x 1000 texels, so the peak grew with the tree's depth: with the area, not the tile
// (`tiles_benchmark`: +55 MiB from 1x to 2x, where the tree gained a level). Written to a file of the
// output's temporary folder instead and read back when the parent is made, a waiting tile costs disk, not
// memory.
//
// The file is lutex's own (not a format to exchange): "lutex-waiting-tile 1", then each array as a count
// and its values' bytes as this machine lays them out (doubles, floats and 32-bit integers), the atlas
// pages as rows, columns and CV_32FC3 texels; counts and sizes through lib/util/binary_io.h. Read back,
// everything is as it was, to the bit.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "texturing/textured_mesh.h"
#include "texturing/tile_mesh.h"

namespace lutex {

struct WaitingTile {
  TileMesh geometry;
  // Its mesh is geometry.mesh (written once); up and georeference are not kept (the parent's own are
  // the bake's).
  TexturedMesh halved_texture;
  std::vector<std::uint32_t> view_of_face;  // the view each face was textured from (kNoView: none)
};

// Throws std::runtime_error naming the file when it cannot be written whole (the disk is full).
void WriteWaitingTile(const WaitingTile& tile, const std::filesystem::path& path);

// Throws std::runtime_error naming the file when it is missing, not a waiting tile or truncated.
WaitingTile ReadWaitingTile(const std::filesystem::path& path);

}  // namespace lutex
