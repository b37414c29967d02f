#include "texturing/face_adjacency.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace lutex {

FaceAdjacency::FaceAdjacency(const Mesh& mesh) {
  // Every edge as (smaller vertex, larger vertex, face), sorted so that the faces of one edge are adjacent.
  struct EdgeOfFace {
    std::uint32_t a, b, face;
    bool operator<(const EdgeOfFace& other) const {
      return std::tie(a, b, face) < std::tie(other.a, other.b, other.face);
    }
  };
  std::vector<EdgeOfFace> edges;
  edges.reserve(3 * mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = mesh.faces[f][k], v = mesh.faces[f][(k + 1) % 3];
      edges.push_back({std::min(u, v), std::max(u, v), f});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    for (std::size_t p = i; p < j; ++p) {
      for (std::size_t q = p + 1; q < j; ++q) {
        if (edges[p].face == edges[q].face) continue;
        pairs.emplace_back(edges[p].face, edges[q].face);
        pairs.emplace_back(edges[q].face, edges[p].face);
      }
    }
    i = j;
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  offsets_.assign(mesh.faces.size() + 1, 0);
  for (const auto& [face, neighbour] : pairs) ++offsets_[face + 1];
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) offsets_[f + 1] += offsets_[f];
  neighbours_.reserve(pairs.size());
  for (const auto& [face, neighbour] : pairs) neighbours_.push_back(neighbour);
}

}  // namespace lutex
