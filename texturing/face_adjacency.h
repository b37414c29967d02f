#pragma once

// Which faces of a triangle mesh share an edge. On a manifold mesh each face has at most 3 neighbours;
// at a non-manifold edge every pair of its faces are neighbours.

#include <cstdint>
#include <vector>

#include "lib/geometry/mesh.h"

namespace lutex {

class FaceAdjacency {
 public:
  explicit FaceAdjacency(const Mesh& mesh);

  std::size_t NumFaces() const { return offsets_.size() - 1; }
  // Neighbours of `face`, ascending.
  const std::uint32_t* begin(std::uint32_t face) const { return neighbours_.data() + offsets_[face]; }
  const std::uint32_t* end(std::uint32_t face) const { return neighbours_.data() + offsets_[face + 1]; }
  std::size_t Degree(std::uint32_t face) const { return offsets_[face + 1] - offsets_[face]; }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<std::uint32_t> neighbours_;
};

}  // namespace lutex
