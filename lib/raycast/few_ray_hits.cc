#include "lib/raycast/few_ray_hits.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lutex {

namespace {

// Cells of the grid along each side: fine enough that a downward ray's cell holds few faces' worth of
// rays, coarse enough that a slanted ray crosses few cells.
constexpr int kGridCells = 256;

// Distance along the ray to its crossing of the triangle (either side), or +infinity (Möller and
// Trumbore's test, 1997).
double CrossingDistance(const Ray3d& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const Eigen::Vector3d p = ray.direction.cross(ac);
  const double det = ab.dot(p);
  if (std::abs(det) <= std::numeric_limits<double>::min()) return INFINITY;
  const Eigen::Vector3d from_a = ray.origin - a;
  const double u = from_a.dot(p) / det;
  if (u < 0.0 || u > 1.0) return INFINITY;
  const Eigen::Vector3d q = from_a.cross(ab);
  const double v = ray.direction.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return INFINITY;
  const double t = ac.dot(q) / det;
  return t >= 0.0 ? t : INFINITY;
}

}  // namespace

std::vector<double> FirstHitDistances(const Mesh& mesh, const std::vector<Ray3d>& rays) {
  std::vector<double> distances(rays.size(), INFINITY);
  if (mesh.faces.empty() || rays.empty()) return distances;
  for (const Ray3d& ray : rays) {
    if (!(ray.direction.squaredNorm() > 0.0)) throw std::invalid_argument("a ray has no direction");
  }
  const Eigen::Vector3d low = mesh.BoundsMin(), high = mesh.BoundsMax();
  const Eigen::Vector2d cell_size = ((high - low).head<2>() / kGridCells).cwiseMax(1e-12);
  const auto cell_of = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector2d at = ((point - low).head<2>().array() / cell_size.array()).floor();
    return Eigen::Vector2i(std::clamp(static_cast<int>(at.x()), 0, kGridCells - 1),
                           std::clamp(static_cast<int>(at.y()), 0, kGridCells - 1));
  };

  // Each ray, clipped to the mesh's box, into the cells it crosses (sampled at a quarter cell).
  std::vector<std::vector<std::uint32_t>> rays_of_cell(std::size_t(kGridCells) * kGridCells);
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const Ray3d& ray = rays[r];
    double enter = 0.0, leave = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
      const double d = ray.direction[axis], o = ray.origin[axis];
      if (d == 0.0) {
        if (o < low[axis] || o > high[axis]) leave = -1.0;
        continue;
      }
      const double t0 = (low[axis] - o) / d, t1 = (high[axis] - o) / d;
      enter = std::max(enter, std::min(t0, t1));
      leave = std::min(leave, std::max(t0, t1));
    }
    if (leave < enter) continue;
    const Eigen::Vector3d from = ray.origin + enter * ray.direction, to = ray.origin + leave * ray.direction;
    const double span = ((to - from).head<2>().array() / cell_size.array()).abs().maxCoeff();
    const int steps = 1 + static_cast<int>(std::ceil(4.0 * span));
    std::uint32_t last = std::numeric_limits<std::uint32_t>::max();
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2i cell = cell_of(from + (to - from) * (double(s) / steps));
      const std::uint32_t index = static_cast<std::uint32_t>(cell.y() * kGridCells + cell.x());
      if (index == last) continue;
      std::vector<std::uint32_t>& here = rays_of_cell[index];
      if (here.empty() || here.back() != r) here.push_back(static_cast<std::uint32_t>(r));
      last = index;
    }
  }

  // Each face against the rays of the cells its box covers and their neighbours: where a ray crosses a
  // face, a sample of it lies within an eighth of a cell, in that cell or the next.
  for (const Mesh::Face& face : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[face[0]];
    const Eigen::Vector3d& b = mesh.vertices[face[1]];
    const Eigen::Vector3d& c = mesh.vertices[face[2]];
    const Eigen::Vector2i first = (cell_of(a.cwiseMin(b).cwiseMin(c)).array() - 1).cwiseMax(0);
    const Eigen::Vector2i last = (cell_of(a.cwiseMax(b).cwiseMax(c)).array() + 1).cwiseMin(kGridCells - 1);
    for (int y = first.y(); y <= last.y(); ++y) {
      for (int x = first.x(); x <= last.x(); ++x) {
        for (std::uint32_t r : rays_of_cell[std::size_t(y) * kGridCells + x]) {
          distances[r] = std::min(distances[r], CrossingDistance(rays[r], a, b, c));
        }
      }
    }
  }
  return distances;
}

}  // namespace lutex
