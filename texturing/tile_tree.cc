#include "texturing/tile_tree.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <stdexcept>

namespace lutex {

void TileTreeOptions::Check() const {
  if (max_faces < 1) throw std::invalid_argument("a tile must hold at least one face");
  if (max_depth < 0 || max_depth > 24) throw std::invalid_argument("the tile depth must be in [0, 24]");
}

std::size_t TileTree::NumLeaves() const {
  return static_cast<std::size_t>(
      std::count_if(nodes.begin(), nodes.end(), [](const TileNode& node) { return node.children.empty(); }));
}

TileTree PartitionIntoTiles(const Mesh& mesh, const Eigen::Matrix3d& tiles_from_model, const TileTreeOptions& options) {
  options.Check();
  if (mesh.faces.empty()) throw std::invalid_argument("tiles: the mesh has no faces");
  if (mesh.faces.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("tiles: the mesh has more faces than a tile tree can number");
  // A face's centroid in the tiles frame's horizontal, computed again where needed rather than held
  // (16 bytes a face): the same expression gives the same bits, so the tree does not change.
  const auto centroid_of = [&](std::uint32_t f) -> Eigen::Vector2d {
    const Mesh::Face& face = mesh.faces[f];
    const Eigen::Vector3d centroid =
        tiles_from_model * ((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0);
    return centroid.head<2>();
  };
  Eigen::AlignedBox2d bounds;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) bounds.extend(centroid_of(static_cast<std::uint32_t>(f)));
  // A square footprint, so that every tile is square.
  const double side = std::max(bounds.sizes().maxCoeff(), 1e-9);
  const Eigen::Vector2d low = bounds.center() - Eigen::Vector2d::Constant(0.5 * side);

  // All faces in one array, each node a range of it; a split sorts its range stably by quadrant, so
  // every range stays ascending. Peak: the array, one split's copy, and at the end the leaves' lists.
  std::vector<std::uint32_t> order(mesh.faces.size());
  for (std::size_t f = 0; f < order.size(); ++f) order[f] = static_cast<std::uint32_t>(f);
  std::vector<std::pair<std::size_t, std::size_t>> ranges = {{0, order.size()}};  // per node: [begin, end)
  std::vector<std::uint32_t> split;
  std::vector<std::uint8_t> quadrant_of;

  TileTree tree;
  TileNode root;
  root.name = "0";
  root.footprint = Eigen::AlignedBox2d(low, low + Eigen::Vector2d::Constant(side));
  tree.nodes.push_back(std::move(root));
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const auto [begin, end] = ranges[n];
    if (end - begin <= options.max_faces || tree.nodes[n].depth >= options.max_depth) continue;
    const Eigen::Vector2d centre = tree.nodes[n].footprint.center();
    quadrant_of.resize(end - begin);
    std::array<std::size_t, 4> counts{};
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d centroid = centroid_of(order[i]);
      const int quadrant = (centroid.x() >= centre.x() ? 1 : 0) + (centroid.y() >= centre.y() ? 2 : 0);
      quadrant_of[i - begin] = static_cast<std::uint8_t>(quadrant);
      ++counts[quadrant];
    }
    std::array<std::size_t, 4> next{};
    for (int q = 1; q < 4; ++q) next[q] = next[q - 1] + counts[q - 1];
    split.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i) split[next[quadrant_of[i - begin]]++] = order[i];
    std::copy(split.begin(), split.end(), order.begin() + static_cast<std::ptrdiff_t>(begin));
    std::size_t child_begin = begin;
    for (int q = 0; q < 4; ++q) {
      if (counts[q] == 0) continue;
      TileNode child;
      child.depth = tree.nodes[n].depth + 1;
      child.name = tree.nodes[n].name + "_" + std::to_string(q);
      const Eigen::Vector2d corner = tree.nodes[n].footprint.min();
      const Eigen::Vector2d half = 0.5 * tree.nodes[n].footprint.sizes();
      const Eigen::Vector2d child_low = corner + Eigen::Vector2d((q & 1) ? half.x() : 0.0, (q & 2) ? half.y() : 0.0);
      child.footprint = Eigen::AlignedBox2d(child_low, child_low + half);
      tree.nodes[n].children.push_back(tree.nodes.size());
      tree.nodes.push_back(std::move(child));
      ranges.emplace_back(child_begin, child_begin + counts[q]);
      child_begin += counts[q];
    }
  }
  split = {};
  quadrant_of = {};
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    if (!tree.nodes[n].children.empty()) continue;
    tree.nodes[n].faces.assign(order.begin() + static_cast<std::ptrdiff_t>(ranges[n].first),
                               order.begin() + static_cast<std::ptrdiff_t>(ranges[n].second));
  }
  return tree;
}

}  // namespace lutex
