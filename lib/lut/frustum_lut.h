#pragma once

// The lookup table of light-and-water effects in the camera's view frustum (paper Sec. 2.1, "3-D lookup
// table"): per node, per colour channel, a signal factor alpha and a backscatter beta, so that a pixel
// seeing albedo rho at point x (camera frame) with shading cos_theta reads I = alpha(x) cos_theta rho +
// beta(x) (see lib/model/image_formation.h).
//
// Grid. Across the image: `nx` x `ny` cells over normalised image coordinates (s, t) = (u / width,
// v / height) in [0, 1], with nodes on the cell corners: node (i, j) sits at (i / nx, j / ny), so there are
// (nx + 1) x (ny + 1) node columns. In depth: `nz` slabs, node planes at planar depths z_0 = z_near ...
// z_{nz-1} = z_far, spaced uniformly in z or in 1/z. Lookups are trilinear, clamped at the borders
// (outside the image or depth range, the nearest border value). Corner-aligned nodes make coarse-to-fine
// levels nest: every node of a 4 x 3 grid is a node of the 20 x 15 and 40 x 30 grids.
//
// Alpha interpolation. The signal factor falls off roughly as 1 / z^2 (inverse-square law from lights
// near the camera), which trilinear interpolation between 10 slabs follows poorly: restoring with a
// perfect 40 x 30 x 10 LUT then errs by 2 % of full scale (median; 0.13 % with 30 slabs). With
// AlphaInterpolation::kInverseSquare (the default) lookups interpolate alpha * z^2 and divide by z^2,
// which removes the fall-off: the same perfect 10-slab LUT then errs by 0.44 % (95th percentile 0.83 %
// instead of 6.1 %). Nodes still store the physical
// alpha at the node, and lookups stay linear in the node values (weights w_i z_i^2 / z^2), so the
// calibration is unchanged. Beta (accumulated backscatter) is always trilinear.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lib/model/forward_scatter.h"
#include "lib/model/shading.h"

namespace lutex {

enum class DepthSpacing { kUniformZ, kUniformInverseZ };
enum class AlphaInterpolation { kTrilinear, kInverseSquare };

struct FrustumLutGrid {
  int nx = 40;  // cells across
  int ny = 30;  // cells down
  int nz = 10;  // slabs (node planes in depth)
  double z_near = 0.5;
  double z_far = 5.0;
  DepthSpacing spacing = DepthSpacing::kUniformInverseZ;
  AlphaInterpolation alpha_interpolation = AlphaInterpolation::kInverseSquare;
  // Size of the images the LUT is for; lookups take pixel coordinates in this size.
  int image_width = 0;
  int image_height = 0;
  // How the model shades (lib/model/shading.h: one light position, by default the camera centre, or the
  // light rig). Part of the LUT's meaning: restoration must shade as the calibration did.
  Shading shading;
  // The forward scattering taken out of every image before the LUT was fitted (lib/model/forward_scatter.h);
  // none in air or when switched off. Part of the LUT's meaning: restoration must take out the same.
  ForwardScatter forward_scatter;

  // Throws std::invalid_argument naming the problem.
  void Check() const;
  int NodesX() const { return nx + 1; }
  int NodesY() const { return ny + 1; }
  int NumNodes() const { return NodesX() * NodesY() * nz; }
  int NodeIndex(int i, int j, int k) const { return (k * NodesY() + j) * NodesX() + i; }
  // Planar depth of slab k.
  double SlabDepth(int k) const;
  // Continuous slab coordinate of depth z in [0, nz - 1] (clamped).
  double SlabCoordinate(double z) const;
  bool operator==(const FrustumLutGrid& other) const;
};

// The value stored per node: alpha (signal factor) and beta (backscatter), per RGB channel.
struct LutNode {
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();
  Eigen::Vector3d beta = Eigen::Vector3d::Zero();
};

// Up to 8 nodes and their weights in a lookup: beta = sum weight_i beta_i (trilinear, summing to 1),
// alpha = sum alpha_weight_i alpha_i (equal to weight_i, or weight_i z_i^2 / z^2 for kInverseSquare).
// The calibration builds its residuals from these.
struct NodeWeights {
  std::array<int, 8> node{};
  std::array<double, 8> weight{};
  std::array<double, 8> alpha_weight{};
  int count = 0;
};

class FrustumLut {
 public:
  FrustumLut() = default;
  // All nodes zero. Throws on an invalid grid.
  explicit FrustumLut(const FrustumLutGrid& grid);

  const FrustumLutGrid& grid() const { return grid_; }
  LutNode& node(int i, int j, int k) { return nodes_[grid_.NodeIndex(i, j, k)]; }
  const LutNode& node(int i, int j, int k) const { return nodes_[grid_.NodeIndex(i, j, k)]; }
  LutNode& node(int index) { return nodes_[index]; }
  const LutNode& node(int index) const { return nodes_[index]; }
  // Camera-frame position of node (i, j, k) needs a camera; the node's pixel is this.
  Eigen::Vector2d NodePixel(int i, int j) const;

  // The nodes and weights of a lookup at pixel (u, v) (image of grid().image_width x image_height) and
  // planar depth z.
  NodeWeights Weights(double u, double v, double z) const;
  // Trilinear lookup.
  LutNode Lookup(double u, double v, double z) const;

  // This LUT's values on another grid (same image size), by trilinear lookup at the new nodes.
  FrustumLut Resampled(const FrustumLutGrid& grid) const;

 private:
  FrustumLutGrid grid_;
  std::vector<LutNode> nodes_;
  std::vector<double> slab_depth_squared_;  // z_k^2, for inverse-square alpha weights
};

}  // namespace lutex
