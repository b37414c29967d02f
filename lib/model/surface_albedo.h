#pragma once

// The true albedo of a mesh's surface (linear RGB), for the simulator: one constant, the mesh's vertex
// colours (8-bit sRGB, linearised and interpolated), its face colours (8-bit sRGB, linearised), or a texture through the mesh's texture coordinates
// (per-corner if present, else per-vertex; v = 0 at the bottom row; nearest texel, as the shared Blender
// scenes sample it, or bilinear).

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/geometry/mesh.h"

namespace lutex {

class SurfaceAlbedo {
 public:
  static SurfaceAlbedo Constant(const Eigen::Vector3d& albedo);
  // Throws when the mesh has no vertex colours.
  static SurfaceAlbedo FromVertexColors(const Mesh& mesh);
  // Throws when the mesh has no face colours.
  static SurfaceAlbedo FromFaceColors(const Mesh& mesh);
  // `texture` is linear RGB CV_32FC3. Throws when the mesh has no texture coordinates.
  static SurfaceAlbedo FromTexture(const Mesh& mesh, const cv::Mat& texture, bool nearest = true);

  // Albedo at barycentrics (b1, b2) of face `face`: (1 - b1 - b2) v0 + b1 v1 + b2 v2.
  Eigen::Vector3d At(const Mesh& mesh, int face, double b1, double b2) const;

 private:
  enum class Kind { kConstant, kVertexColors, kFaceColors, kTexture };
  Kind kind_ = Kind::kConstant;
  Eigen::Vector3d constant_ = Eigen::Vector3d::Constant(0.5);
  std::vector<Eigen::Vector3d> vertex_albedo_;  // or face albedo for kFaceColors
  cv::Mat texture_;
  bool nearest_ = true;
};

}  // namespace lutex
