#include "texturing/tile_tree.h"

#include <algorithm>
#include <array>
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
  // Each face's centroid in the tiles frame's horizontal.
  std::vector<Eigen::Vector2d> centroids(mesh.faces.size());
  Eigen::AlignedBox2d bounds;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Mesh::Face& face = mesh.faces[f];
    const Eigen::Vector3d centroid =
        tiles_from_model * ((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0);
    centroids[f] = centroid.head<2>();
    bounds.extend(centroids[f]);
  }
  // A square footprint, so that every tile is square.
  const double side = std::max(bounds.sizes().maxCoeff(), 1e-9);
  const Eigen::Vector2d low = bounds.center() - Eigen::Vector2d::Constant(0.5 * side);

  TileTree tree;
  TileNode root;
  root.name = "0";
  root.footprint = Eigen::AlignedBox2d(low, low + Eigen::Vector2d::Constant(side));
  root.faces.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) root.faces[f] = static_cast<std::uint32_t>(f);
  tree.nodes.push_back(std::move(root));
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    if (tree.nodes[n].faces.size() <= options.max_faces || tree.nodes[n].depth >= options.max_depth) continue;
    const Eigen::Vector2d centre = tree.nodes[n].footprint.center();
    std::array<std::vector<std::uint32_t>, 4> quadrants;
    for (std::uint32_t f : tree.nodes[n].faces) {
      const int quadrant = (centroids[f].x() >= centre.x() ? 1 : 0) + (centroids[f].y() >= centre.y() ? 2 : 0);
      quadrants[quadrant].push_back(f);
    }
    tree.nodes[n].faces = {};
    for (int q = 0; q < 4; ++q) {
      if (quadrants[q].empty()) continue;
      TileNode child;
      child.depth = tree.nodes[n].depth + 1;
      child.name = tree.nodes[n].name + "_" + std::to_string(q);
      const Eigen::Vector2d corner = tree.nodes[n].footprint.min();
      const Eigen::Vector2d half = 0.5 * tree.nodes[n].footprint.sizes();
      const Eigen::Vector2d child_low = corner + Eigen::Vector2d((q & 1) ? half.x() : 0.0, (q & 2) ? half.y() : 0.0);
      child.footprint = Eigen::AlignedBox2d(child_low, child_low + half);
      child.faces = std::move(quadrants[q]);
      tree.nodes[n].children.push_back(tree.nodes.size());
      tree.nodes.push_back(std::move(child));
    }
  }
  return tree;
}

}  // namespace lutex
