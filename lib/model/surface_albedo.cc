#include "lib/model/surface_albedo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "lib/image/image_io.h"

namespace lutex {
namespace {

std::vector<Eigen::Vector3d> Linearised(const std::vector<Eigen::Matrix<std::uint8_t, 3, 1>>& srgb8) {
  std::vector<Eigen::Vector3d> linear;
  linear.reserve(srgb8.size());
  for (const auto& colour : srgb8) {
    linear.emplace_back(SrgbToLinear(colour[0] / 255.0), SrgbToLinear(colour[1] / 255.0), SrgbToLinear(colour[2] / 255.0));
  }
  return linear;
}

}  // namespace

SurfaceAlbedo SurfaceAlbedo::Constant(const Eigen::Vector3d& albedo) {
  SurfaceAlbedo result;
  result.constant_ = albedo;
  return result;
}

SurfaceAlbedo SurfaceAlbedo::FromVertexColors(const Mesh& mesh) {
  if (mesh.vertex_colors.empty()) throw std::invalid_argument("the mesh has no vertex colours");
  SurfaceAlbedo result;
  result.kind_ = Kind::kVertexColors;
  result.vertex_albedo_ = Linearised(mesh.vertex_colors);
  return result;
}

SurfaceAlbedo SurfaceAlbedo::FromFaceColors(const Mesh& mesh) {
  if (mesh.face_colors.empty()) throw std::invalid_argument("the mesh has no face colours");
  SurfaceAlbedo result;
  result.kind_ = Kind::kFaceColors;
  result.vertex_albedo_ = Linearised(mesh.face_colors);
  return result;
}

SurfaceAlbedo SurfaceAlbedo::FromTexture(const Mesh& mesh, const cv::Mat& texture, bool nearest) {
  if (mesh.vertex_texcoords.empty() && mesh.corner_texcoords.empty()) {
    throw std::invalid_argument("the mesh has no texture coordinates");
  }
  CV_Assert(texture.type() == CV_32FC3 && !texture.empty());
  SurfaceAlbedo result;
  result.kind_ = Kind::kTexture;
  result.texture_ = texture;
  result.nearest_ = nearest;
  return result;
}

Eigen::Vector3d SurfaceAlbedo::At(const Mesh& mesh, int face, double b1, double b2) const {
  const double b0 = 1.0 - b1 - b2;
  const Mesh::Face& corners = mesh.faces[face];
  switch (kind_) {
    case Kind::kConstant: return constant_;
    case Kind::kFaceColors: return vertex_albedo_[face];
    case Kind::kVertexColors:
      return b0 * vertex_albedo_[corners[0]] + b1 * vertex_albedo_[corners[1]] + b2 * vertex_albedo_[corners[2]];
    case Kind::kTexture: {
      Eigen::Vector2f uv;
      if (!mesh.corner_texcoords.empty()) {
        const auto& c = mesh.corner_texcoords[face];
        uv = static_cast<float>(b0) * c[0] + static_cast<float>(b1) * c[1] + static_cast<float>(b2) * c[2];
      } else {
        uv = static_cast<float>(b0) * mesh.vertex_texcoords[corners[0]] +
             static_cast<float>(b1) * mesh.vertex_texcoords[corners[1]] +
             static_cast<float>(b2) * mesh.vertex_texcoords[corners[2]];
      }
      // Texture row 0 is v = 1.
      const double x = static_cast<double>(uv.x()) * texture_.cols;
      const double y = (1.0 - static_cast<double>(uv.y())) * texture_.rows;
      if (nearest_) {
        const int col = std::clamp(static_cast<int>(std::floor(x)), 0, texture_.cols - 1);
        const int row = std::clamp(static_cast<int>(std::floor(y)), 0, texture_.rows - 1);
        const cv::Vec3f texel = texture_.at<cv::Vec3f>(row, col);
        return {texel[0], texel[1], texel[2]};
      }
      cv::Mat patch;
      cv::getRectSubPix(texture_, cv::Size(1, 1), cv::Point2f(static_cast<float>(x - 0.5), static_cast<float>(y - 0.5)), patch);
      const cv::Vec3f texel = patch.at<cv::Vec3f>(0, 0);
      return {texel[0], texel[1], texel[2]};
    }
  }
  return constant_;
}

}  // namespace lutex
