#pragma once

// tileset.json of OGC 3D Tiles 1.1: the tree of a tiled bake, for CesiumJS and the viewers built on it.
//
//   {"asset": {"version": "1.1", "generator": "lutex", "extras": {"lutex": {...}}},
//    "geometricError": E,
//    "root": {"transform": [16 numbers, column-major], "boundingVolume": {"box": [12 numbers]},
//             "geometricError": e, "refine": "REPLACE", "content": {"uri": "0.glb"},
//             "children": [...]}}
//
// Bounding volumes are boxes in the tiles frame (gltf_frame.h: +Z up), axis-aligned there: centre and
// three half-axis vectors, each at least 0.5 mm long. Only the root has a transform: the tiles frame to Earth-centred, Earth-fixed
// coordinates (EPSG:4978, metres) for a georeferenced model, absent otherwise. `refine` is REPLACE on
// the root and inherited by every tile: a tile's children, once loaded, are drawn instead of it.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lutex {

struct TilesetTile {
  Eigen::AlignedBox3d box;        // in the tiles frame
  double geometric_error = 0.0;   // metres: the error of drawing this tile instead of its children
  std::string content_uri;        // relative to tileset.json; empty: no content
  std::vector<std::size_t> children;  // indices in Tileset::tiles
};

struct Tileset {
  std::vector<TilesetTile> tiles;  // the root first
  // The tiles frame to ECEF; absent for a model that is not georeferenced.
  std::optional<Eigen::Matrix4d> ecef_from_tiles;
  // The error of drawing nothing at all (metres).
  double geometric_error = 0.0;
  // Written as asset.extras.lutex (a JSON object's text; empty: none).
  std::string lutex_extras_json;
};

// Throws std::invalid_argument when the tree is not a tree rooted at 0, a box is empty, an error is
// negative or a child's error is above its parent's; std::runtime_error naming `path` when it cannot be
// written (atomically, so a failure leaves no partial file).
void WriteTilesetJson(const Tileset& tileset, const std::filesystem::path& path);

}  // namespace lutex
