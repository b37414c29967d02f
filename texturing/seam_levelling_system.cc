#include "texturing/seam_levelling_system.h"

#include <algorithm>
#include <stdexcept>

namespace lutex {

std::array<double, 4> SeamPointCoefficients(float t) {
  const double s = t;
  return {1.0 - s, s, -(1.0 - s), -s};
}

SeamLevellingSystem::SeamLevellingSystem(std::size_t num_unknowns, double fade, double smoothness)
    : smoothness_(smoothness), diagonal_(num_unknowns, fade), points_diagonal_(num_unknowns, 0.0) {}

void SeamLevellingSystem::AddEdge(int i, int j) {
  if (i >= 0) diagonal_[i] += smoothness_;
  if (j >= 0) diagonal_[j] += smoothness_;
  if (i < 0 || j < 0) return;
  const auto low = static_cast<std::uint64_t>(std::min(i, j)), high = static_cast<std::uint64_t>(std::max(i, j));
  edge_keys_.push_back(low << 32 | high);
}

void SeamLevellingSystem::FinishEdges() {
  std::sort(edge_keys_.begin(), edge_keys_.end());
  for (std::size_t k = 0; k < edge_keys_.size();) {
    std::size_t end = k;
    while (end < edge_keys_.size() && edge_keys_[end] == edge_keys_[k]) ++end;
    edge_i_.push_back(static_cast<std::uint32_t>(edge_keys_[k] >> 32));
    edge_j_.push_back(static_cast<std::uint32_t>(edge_keys_[k] & 0xffffffffu));
    edge_faces_.push_back(static_cast<std::uint8_t>(std::min<std::size_t>(end - k, 255)));
    k = end;
  }
  edge_keys_ = {};
}

void SeamLevellingSystem::AddPoint(const std::array<int, 4>& unknowns, float t, double weight) {
  const std::array<double, 4> c = SeamPointCoefficients(t);
  for (int r = 0; r < 4; ++r) {
    if (unknowns[r] >= 0) points_diagonal_[unknowns[r]] += weight * c[r] * c[r];
  }
  points_.push_back({unknowns, t, weight});
}

void SeamLevellingSystem::ClearPoints() {
  points_.clear();
  std::fill(points_diagonal_.begin(), points_diagonal_.end(), 0.0);
}

void SeamLevellingSystem::Apply(const ChannelVectors& x, ChannelVectors* y) const {
  y->resize(x.rows(), 3);
  for (Eigen::Index u = 0; u < x.rows(); ++u) y->row(u) = diagonal_[u] * x.row(u);
  for (std::size_t e = 0; e < edge_i_.size(); ++e) {
    const double weight = smoothness_ * edge_faces_[e];
    const auto i = static_cast<Eigen::Index>(edge_i_[e]), j = static_cast<Eigen::Index>(edge_j_[e]);
    y->row(i) -= weight * x.row(j);
    y->row(j) -= weight * x.row(i);
  }
  for (const Point& point : points_) {
    const std::array<double, 4> c = SeamPointCoefficients(point.t);
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int r = 0; r < 4; ++r) {
      if (point.unknowns[r] >= 0) sum += c[r] * x.row(point.unknowns[r]);
    }
    for (int r = 0; r < 4; ++r) {
      if (point.unknowns[r] >= 0) y->row(point.unknowns[r]) += point.weight * c[r] * sum;
    }
  }
}

int SeamLevellingSystem::Solve(const ChannelVectors& b, int max_iterations, double tolerance, ChannelVectors* x) const {
  const Eigen::Index n = static_cast<Eigen::Index>(num_unknowns());
  if (b.rows() != n) throw std::invalid_argument("seam levelling: one right-hand side row per unknown");
  Eigen::VectorXd inverse_diagonal(n);
  for (Eigen::Index u = 0; u < n; ++u) {
    const double d = diagonal_[u] + points_diagonal_[u];
    inverse_diagonal[u] = d > 0.0 ? 1.0 / d : 1.0;
  }
  x->setZero(n, 3);
  // The preconditioned residual z = D^-1 r is kept for one channel at a time.
  ChannelVectors residual = b, direction = inverse_diagonal.asDiagonal() * residual, product(n, 3);
  Eigen::VectorXd z(n);
  Eigen::Array3d threshold, rz;
  std::array<bool, 3> active{};
  std::array<int, 3> iterations{};
  for (int c = 0; c < 3; ++c) {
    threshold[c] = tolerance * tolerance * b.col(c).squaredNorm();
    rz[c] = residual.col(c).dot(direction.col(c));
    active[c] = residual.col(c).squaredNorm() > threshold[c];
    if (!active[c]) direction.col(c).setZero();
  }
  for (int iteration = 1; iteration <= max_iterations && (active[0] || active[1] || active[2]); ++iteration) {
    Apply(direction, &product);
    for (int c = 0; c < 3; ++c) {
      if (!active[c]) continue;
      const double step = rz[c] / direction.col(c).dot(product.col(c));
      x->col(c) += step * direction.col(c);
      residual.col(c) -= step * product.col(c);
      iterations[c] = iteration;
      if (residual.col(c).squaredNorm() < threshold[c]) {
        active[c] = false;
        direction.col(c).setZero();
        continue;
      }
      z = inverse_diagonal.cwiseProduct(residual.col(c));
      const double rz_new = residual.col(c).dot(z);
      direction.col(c) = z + (rz_new / rz[c]) * direction.col(c);
      rz[c] = rz_new;
    }
  }
  return *std::max_element(iterations.begin(), iterations.end());
}

}  // namespace lutex
