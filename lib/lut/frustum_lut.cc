#include "lib/lut/frustum_lut.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lutex {
namespace {

// Index of the lower node and the fraction towards the upper one for a continuous coordinate in
// [0, count - 1]; clamped.
void Split(double coordinate, int count, int* lower, double* fraction) {
  if (count <= 1) {
    *lower = 0;
    *fraction = 0.0;
    return;
  }
  const double clamped = std::clamp(coordinate, 0.0, static_cast<double>(count - 1));
  *lower = std::min(static_cast<int>(std::floor(clamped)), count - 2);
  *fraction = clamped - *lower;
}

}  // namespace

void FrustumLutGrid::Check() const {
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("LUT grid needs nx, ny, nz >= 1");
  if (nx > 4096 || ny > 4096 || nz > 4096) throw std::invalid_argument("LUT grid is implausibly large");
  // NumNodes() and the file's value count (6 per node) are ints.
  if (static_cast<long long>(nx + 1) * (ny + 1) * nz * 6 > std::numeric_limits<int>::max()) {
    throw std::invalid_argument("LUT grid is implausibly large (" + std::to_string(nx) + " x " + std::to_string(ny) +
                                " x " + std::to_string(nz) + " cells)");
  }
  if (!(z_near > 0.0) || !(z_far >= z_near) || !std::isfinite(z_far)) {
    throw std::invalid_argument("LUT depth range needs 0 < z_near <= z_far (got " + std::to_string(z_near) + ", " +
                                std::to_string(z_far) + ")");
  }
  if (nz > 1 && z_far == z_near) throw std::invalid_argument("LUT with several slabs needs z_far > z_near");
  if (image_width <= 0 || image_height <= 0) throw std::invalid_argument("LUT grid needs the image size");
  forward_scatter.Check();
}

double FrustumLutGrid::SlabDepth(int k) const {
  if (nz == 1) return z_near;
  const double t = static_cast<double>(k) / (nz - 1);
  if (spacing == DepthSpacing::kUniformZ) return z_near + t * (z_far - z_near);
  return 1.0 / (1.0 / z_near + t * (1.0 / z_far - 1.0 / z_near));
}

double FrustumLutGrid::SlabCoordinate(double z) const {
  if (nz == 1) return 0.0;
  double t;
  if (spacing == DepthSpacing::kUniformZ) {
    t = (z - z_near) / (z_far - z_near);
  } else {
    t = (1.0 / z_near - 1.0 / std::max(z, 1e-12)) / (1.0 / z_near - 1.0 / z_far);
  }
  return std::clamp(t, 0.0, 1.0) * (nz - 1);
}

bool FrustumLutGrid::operator==(const FrustumLutGrid& other) const {
  return nx == other.nx && ny == other.ny && nz == other.nz && z_near == other.z_near && z_far == other.z_far &&
         spacing == other.spacing && alpha_interpolation == other.alpha_interpolation &&
         image_width == other.image_width && image_height == other.image_height &&
         shading == other.shading && forward_scatter == other.forward_scatter;
}

FrustumLut::FrustumLut(const FrustumLutGrid& grid) : grid_(grid) {
  grid_.Check();
  nodes_.resize(static_cast<std::size_t>(grid_.NumNodes()));
  for (int k = 0; k < grid_.nz; ++k) slab_depth_squared_.push_back(grid_.SlabDepth(k) * grid_.SlabDepth(k));
}

Eigen::Vector2d FrustumLut::NodePixel(int i, int j) const {
  return {static_cast<double>(i) / grid_.nx * grid_.image_width, static_cast<double>(j) / grid_.ny * grid_.image_height};
}

NodeWeights FrustumLut::Weights(double u, double v, double z) const {
  int i0, j0, k0;
  double fx, fy, fz;
  Split(u / grid_.image_width * grid_.nx, grid_.NodesX(), &i0, &fx);
  Split(v / grid_.image_height * grid_.ny, grid_.NodesY(), &j0, &fy);
  Split(grid_.SlabCoordinate(z), grid_.nz, &k0, &fz);
  // Depth at which alpha * z^2 is divided back, clamped like the lookup itself (one slab: its depth).
  const double clamped_z = grid_.nz == 1 ? grid_.z_near : std::clamp(z, grid_.z_near, grid_.z_far);
  const double inverse_clamped_z2 =
      grid_.alpha_interpolation == AlphaInterpolation::kInverseSquare ? 1.0 / (clamped_z * clamped_z) : 0.0;
  NodeWeights weights;
  for (int corner = 0; corner < 8; ++corner) {
    const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
    const double w = (di ? fx : 1.0 - fx) * (dj ? fy : 1.0 - fy) * (dk ? fz : 1.0 - fz);
    if (w == 0.0) continue;
    const int index = grid_.NodeIndex(std::min(i0 + di, grid_.nx), std::min(j0 + dj, grid_.ny),
                                      std::min(k0 + dk, grid_.nz - 1));
    weights.node[weights.count] = index;
    weights.weight[weights.count] = w;
    weights.alpha_weight[weights.count] =
        inverse_clamped_z2 > 0.0 ? w * slab_depth_squared_[std::min(k0 + dk, grid_.nz - 1)] * inverse_clamped_z2 : w;
    ++weights.count;
  }
  return weights;
}

// The same interpolation as Weights(), computed directly (it runs once per pixel of every restored image):
// bilinear within the two slabs around z, then along z.
LutNode FrustumLut::Lookup(double u, double v, double z) const {
  int i0, j0, k0;
  double fx, fy, fz;
  Split(u / grid_.image_width * grid_.nx, grid_.NodesX(), &i0, &fx);
  Split(v / grid_.image_height * grid_.ny, grid_.NodesY(), &j0, &fy);
  Split(grid_.SlabCoordinate(z), grid_.nz, &k0, &fz);
  const int i1 = std::min(i0 + 1, grid_.nx), j1 = std::min(j0 + 1, grid_.ny), k1 = std::min(k0 + 1, grid_.nz - 1);
  const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  LutNode slab[2];
  const int ks[2] = {k0, k1};
  for (int s = 0; s < 2; ++s) {
    const LutNode& n00 = nodes_[grid_.NodeIndex(i0, j0, ks[s])];
    const LutNode& n10 = nodes_[grid_.NodeIndex(i1, j0, ks[s])];
    const LutNode& n01 = nodes_[grid_.NodeIndex(i0, j1, ks[s])];
    const LutNode& n11 = nodes_[grid_.NodeIndex(i1, j1, ks[s])];
    slab[s].alpha = w00 * n00.alpha + w10 * n10.alpha + w01 * n01.alpha + w11 * n11.alpha;
    slab[s].beta = w00 * n00.beta + w10 * n10.beta + w01 * n01.beta + w11 * n11.beta;
  }
  double alpha_scale[2] = {1.0, 1.0};
  if (grid_.alpha_interpolation == AlphaInterpolation::kInverseSquare) {
    const double clamped_z = grid_.nz == 1 ? grid_.z_near : std::clamp(z, grid_.z_near, grid_.z_far);
    alpha_scale[0] = slab_depth_squared_[k0] / (clamped_z * clamped_z);
    alpha_scale[1] = slab_depth_squared_[k1] / (clamped_z * clamped_z);
  }
  LutNode result;
  result.alpha = (1 - fz) * alpha_scale[0] * slab[0].alpha + fz * alpha_scale[1] * slab[1].alpha;
  result.beta = (1 - fz) * slab[0].beta + fz * slab[1].beta;
  return result;
}

FrustumLut FrustumLut::Resampled(const FrustumLutGrid& grid) const {
  if (grid.image_width != grid_.image_width || grid.image_height != grid_.image_height) {
    throw std::invalid_argument("resampling a LUT cannot change its image size");
  }
  FrustumLut result(grid);
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        const Eigen::Vector2d pixel = result.NodePixel(i, j);
        result.node(i, j, k) = Lookup(pixel.x(), pixel.y(), grid.SlabDepth(k));
      }
    }
  }
  return result;
}

}  // namespace lutex
