#include "texturing/tileset_json.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lib/util/file_streams.h"

namespace lutex {

namespace {

void CheckTree(const Tileset& tileset) {
  if (tileset.tiles.empty()) throw std::invalid_argument("tileset: no tiles");
  std::vector<int> parents(tileset.tiles.size(), 0);
  for (std::size_t t = 0; t < tileset.tiles.size(); ++t) {
    const TilesetTile& tile = tileset.tiles[t];
    if (tile.box.isEmpty()) throw std::invalid_argument("tileset: tile " + std::to_string(t) + " has an empty box");
    if (!(tile.geometric_error >= 0.0)) {
      throw std::invalid_argument("tileset: tile " + std::to_string(t) + " has a negative geometric error");
    }
    for (std::size_t child : tile.children) {
      if (child == 0 || child >= tileset.tiles.size()) throw std::invalid_argument("tileset: a child index is out of range");
      if (++parents[child] > 1) throw std::invalid_argument("tileset: a tile has two parents");
      if (tileset.tiles[child].geometric_error > tile.geometric_error) {
        throw std::invalid_argument("tileset: tile " + std::to_string(child) + "'s geometric error is above its parent's");
      }
    }
  }
  for (std::size_t t = 1; t < tileset.tiles.size(); ++t) {
    if (parents[t] != 1) throw std::invalid_argument("tileset: tile " + std::to_string(t) + " has no parent");
  }
  if (tileset.geometric_error < tileset.tiles[0].geometric_error) {
    throw std::invalid_argument("tileset: its geometric error is below the root's");
  }
}

nlohmann::json TileJson(const Tileset& tileset, std::size_t t) {
  const TilesetTile& tile = tileset.tiles[t];
  const Eigen::Vector3d centre = tile.box.center();
  // A flat tile's box is given 1 mm of thickness: a box of zero extent is degenerate for a viewer's culling.
  const Eigen::Vector3d half = (0.5 * tile.box.sizes()).cwiseMax(Eigen::Vector3d::Constant(0.0005));
  nlohmann::json json;
  json["boundingVolume"]["box"] = {centre.x(), centre.y(), centre.z(), half.x(), 0.0, 0.0,
                                   0.0,        half.y(),   0.0,        0.0,      0.0, half.z()};
  json["geometricError"] = tile.geometric_error;
  if (!tile.content_uri.empty()) json["content"]["uri"] = tile.content_uri;
  if (!tile.children.empty()) {
    json["children"] = nlohmann::json::array();
    for (std::size_t child : tile.children) json["children"].push_back(TileJson(tileset, child));
  }
  return json;
}

}  // namespace

void WriteTilesetJson(const Tileset& tileset, const std::filesystem::path& path) {
  CheckTree(tileset);
  nlohmann::json json;
  json["asset"] = {{"version", "1.1"}, {"generator", "lutex"}};
  if (!tileset.lutex_extras_json.empty()) json["asset"]["extras"]["lutex"] = nlohmann::json::parse(tileset.lutex_extras_json);
  json["geometricError"] = tileset.geometric_error;
  nlohmann::json root = TileJson(tileset, 0);
  root["refine"] = "REPLACE";
  if (tileset.ecef_from_tiles) {
    root["transform"] = nlohmann::json::array();
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) root["transform"].push_back((*tileset.ecef_from_tiles)(row, column));
    }
  }
  json["root"] = std::move(root);
  WriteFileAtomically(path, std::ios::out, [&](std::ostream& stream) { stream << json.dump(1) << "\n"; });
}

}  // namespace lutex
