#include "texturing/tile_tree.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
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

namespace {

// The quadrant of `footprint` that `point` lies in (1 east, 2 north): the one comparison every step uses.
int QuadrantOf(const Eigen::AlignedBox2d& footprint, const Eigen::Vector2d& point) {
  const Eigen::Vector2d centre = footprint.center();
  return (point.x() >= centre.x() ? 1 : 0) + (point.y() >= centre.y() ? 2 : 0);
}

Eigen::AlignedBox2d QuadrantFootprint(const Eigen::AlignedBox2d& footprint, int quadrant) {
  const Eigen::Vector2d half = 0.5 * footprint.sizes();
  const Eigen::Vector2d low =
      footprint.min() + Eigen::Vector2d((quadrant & 1) ? half.x() : 0.0, (quadrant & 2) ? half.y() : 0.0);
  return Eigen::AlignedBox2d(low, low + half);
}

// Most face counters one pass over the faces fills (4 MiB): the levels a pass looks ahead shrink as more
// tiles wait to be split.
constexpr std::size_t kMaxCounters = std::size_t{1} << 20;

// The tree as it is made: each tile's footprint, depth, face count and the four quadrants (-1: empty or
// not split).
struct Square {
  Eigen::AlignedBox2d footprint;
  int depth = 0;
  std::size_t faces = 0;
  std::array<int, 4> quadrants = {-1, -1, -1, -1};
  bool split = false;
};

}  // namespace

// A face's centroid in the tiles frame's horizontal is computed again at each pass rather than held
// (16 bytes a face): the same expression gives the same bits in every pass.
TileTree PartitionIntoTiles(const Mesh& mesh, const Eigen::Matrix3d& tiles_from_model, const TileTreeOptions& options) {
  options.Check();
  if (mesh.faces.empty()) throw std::invalid_argument("tiles: the mesh has no faces");
  if (mesh.faces.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("tiles: the mesh has more faces than a tile tree can number");
  const auto for_each_centroid = [&](const auto& use) {
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const Mesh::Face& face = mesh.faces[f];
      const Eigen::Vector3d centroid =
          tiles_from_model * ((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0);
      use(static_cast<std::uint32_t>(f), Eigen::Vector2d(centroid.head<2>()));
    }
  };
  Eigen::AlignedBox2d bounds;
  for_each_centroid([&](std::uint32_t, const Eigen::Vector2d& centroid) { bounds.extend(centroid); });
  // A square footprint, so that every tile is square.
  const double side = std::max(bounds.sizes().maxCoeff(), 1e-9);
  const Eigen::Vector2d low = bounds.center() - Eigen::Vector2d::Constant(0.5 * side);

  // A tile is split while it holds more than max_faces faces and is above max_depth. Its faces are not
  // held: each pass over them counts, for every tile waiting to be split, its faces in each square a few
  // levels below it, from which those levels are made; tiles still too full at the bottom wait for the
  // next pass. Memory: the counters and, at the end, the leaves' lists.
  std::vector<Square> squares(1);
  squares[0].footprint = Eigen::AlignedBox2d(low, low + Eigen::Vector2d::Constant(side));
  squares[0].faces = mesh.faces.size();
  const auto needs_split = [&](const Square& square) {
    return square.faces > options.max_faces && square.depth < options.max_depth;
  };
  // The square a point lies in among those made.
  const auto square_of = [&](const Eigen::Vector2d& point) {
    int s = 0;
    while (squares[s].split) s = squares[s].quadrants[QuadrantOf(squares[s].footprint, point)];
    return s;
  };
  std::vector<int> waiting;
  if (needs_split(squares[0])) waiting.push_back(0);
  while (!waiting.empty()) {
    int ahead = 1;  // levels counted below each waiting square
    while (waiting.size() << (2 * (ahead + 1)) <= kMaxCounters) ++ahead;
    std::vector<int> slot(squares.size(), -1);  // of each waiting square's counters
    std::vector<int> levels(waiting.size());
    std::vector<std::size_t> first(waiting.size() + 1, 0);
    for (std::size_t w = 0; w < waiting.size(); ++w) {
      slot[waiting[w]] = static_cast<int>(w);
      levels[w] = std::min(ahead, options.max_depth - squares[waiting[w]].depth);
      first[w + 1] = first[w] + (std::size_t{1} << (2 * levels[w]));
    }
    std::vector<std::uint32_t> counts(first.back(), 0);
    for_each_centroid([&](std::uint32_t, const Eigen::Vector2d& centroid) {
      const int s = square_of(centroid);
      if (slot[s] < 0) return;
      const int w = slot[s];
      Eigen::AlignedBox2d footprint = squares[s].footprint;
      std::size_t cell = 0;
      for (int level = 0; level < levels[w]; ++level) {
        const int quadrant = QuadrantOf(footprint, centroid);
        cell = 4 * cell + static_cast<std::size_t>(quadrant);
        footprint = QuadrantFootprint(footprint, quadrant);
      }
      ++counts[first[w] + cell];
    });
    std::vector<int> next;
    for (std::size_t w = 0; w < waiting.size(); ++w) {
      // Splits square `s`, whose faces are counted in counts[begin, begin + 4^below), below it.
      const auto split = [&](const auto& self, int s, std::size_t begin, int below) -> void {
        if (below == 0) {
          next.push_back(s);
          return;
        }
        squares[s].split = true;
        const std::size_t quarter = std::size_t{1} << (2 * (below - 1));
        for (int q = 0; q < 4; ++q) {
          const std::size_t cells = begin + static_cast<std::size_t>(q) * quarter;
          const std::size_t faces = std::accumulate(counts.begin() + static_cast<std::ptrdiff_t>(cells),
                                                    counts.begin() + static_cast<std::ptrdiff_t>(cells + quarter),
                                                    std::size_t{0});
          if (faces == 0) continue;
          Square square;
          square.footprint = QuadrantFootprint(squares[s].footprint, q);
          square.depth = squares[s].depth + 1;
          square.faces = faces;
          const int index = static_cast<int>(squares.size());
          squares[s].quadrants[q] = index;
          squares.push_back(square);
          if (needs_split(squares[index])) self(self, index, cells, below - 1);
        }
      };
      split(split, waiting[w], first[w], levels[w]);
    }
    waiting = std::move(next);
  }

  // The tiles in the order a split of each in turn appends its quadrants: a parent before its children.
  TileTree tree;
  std::vector<int> node_of(squares.size(), -1);
  std::vector<int> order = {0};
  TileNode root;
  root.name = "0";
  root.footprint = squares[0].footprint;
  tree.nodes.push_back(std::move(root));
  node_of[0] = 0;
  for (std::size_t n = 0; n < order.size(); ++n) {
    const Square& square = squares[order[n]];
    for (int q = 0; q < 4; ++q) {
      const int child = square.quadrants[q];
      if (child < 0) continue;
      TileNode node;
      node.depth = squares[child].depth;
      node.name = tree.nodes[n].name + "_" + std::to_string(q);
      node.footprint = squares[child].footprint;
      node_of[child] = static_cast<int>(tree.nodes.size());
      tree.nodes[n].children.push_back(tree.nodes.size());
      tree.nodes.push_back(std::move(node));
      order.push_back(child);
    }
  }
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    if (tree.nodes[n].children.empty()) tree.nodes[n].faces.reserve(squares[order[n]].faces);
  }
  for_each_centroid([&](std::uint32_t f, const Eigen::Vector2d& centroid) {
    tree.nodes[node_of[square_of(centroid)]].faces.push_back(f);
  });
  return tree;
}

}  // namespace lutex
