#pragma once

// The normal equations of seam levelling (seam_levelling.h), held as the terms they are made of rather
// than as a sparse matrix, and solved by preconditioned conjugate gradients for the three channels at
// once.
//
// The system matrix is  A = fade I + smoothness L + sum over seam points w_x c_x c_x^T, with L the graph
// Laplacian of the chart edges between unknowns (an edge to a vertex without an unknown ties its
// other end to 0) and c_x the point's four coefficients (1 - t, t, -(1 - t), -t). Held as:
//   - the diagonal of A (fade and the edges' part; the points' part): 16 bytes an unknown;
//   - the distinct edges between unknowns with how many faces have them (an edge shared by two faces of
//     one view counts twice): 9 bytes an edge, about 3 edges an unknown (8 bytes a face edge while they
//     are gathered);
//   - the seam points: their four unknowns, t and weight, 32 bytes each.
// A sparse matrix of the same system took about 15 entries of 12 bytes an unknown, and twice that while
// it was assembled: at 627,000 unknowns (the 4x-area tiles benchmark) that was the peak of `lutex tiles`.
// A x costs one pass over the edges and the points, as much as the sparse product did.
//
// The solve is Jacobi-preconditioned CG from 0 per channel, to |r| <= tolerance |b|, as Eigen's
// ConjugateGradient with a DiagonalPreconditioner does; single-threaded, so the result does not depend on
// the thread count.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace lutex {

// A seam point's coefficients (1 - t, t, -(1 - t), -t) for its unknowns (p, a), (q, a), (p, b), (q, b):
// the step c_b - c_a left after corrections g is the step minus sum_r coefficient_r g_r.
std::array<double, 4> SeamPointCoefficients(float t);

// One value per unknown and channel, a row per unknown.
using ChannelVectors = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

class SeamLevellingSystem {
 public:
  // `num_unknowns` unknowns; `fade` on the diagonal, `smoothness` the weight of one face's chart edge.
  SeamLevellingSystem(std::size_t num_unknowns, double fade, double smoothness);

  // One face's chart edge between unknowns i and j; -1 for a vertex without an unknown (the other end is
  // then tied to 0). After the last edge, FinishEdges() merges the edges two faces share.
  void AddEdge(int i, int j);
  void FinishEdges();

  // The seam points' terms: the point at t along its edge, its unknowns (p, a), (q, a), (p, b), (q, b)
  // (-1 for a correction that is not an unknown: its part of the step is in the right-hand side) and its
  // weight. ClearPoints() removes them all (for the next round of reweighting).
  void AddPoint(const std::array<int, 4>& unknowns, float t, double weight);
  void ClearPoints();

  std::size_t num_unknowns() const { return diagonal_.size(); }

  // y = A x.
  void Apply(const ChannelVectors& x, ChannelVectors* y) const;

  // Solves A x = b per channel; returns the most iterations any channel took.
  int Solve(const ChannelVectors& b, int max_iterations, double tolerance, ChannelVectors* x) const;

 private:
  struct Point {
    std::array<int, 4> unknowns;
    float t;
    double weight;
  };
  double smoothness_;
  std::vector<double> diagonal_;           // fade and the edges' part of A's diagonal
  std::vector<double> points_diagonal_;    // the points' part
  std::vector<std::uint64_t> edge_keys_;   // while edges are added: (i << 32) | j, i < j, one per face edge
  std::vector<std::uint32_t> edge_i_, edge_j_;
  std::vector<std::uint8_t> edge_faces_;  // how many faces have the edge (weight: that x smoothness)
  std::vector<Point> points_;
};

}  // namespace lutex
