#include "texturing/textured_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lutex {

std::size_t TexturedMesh::NumTexturedFaces() const {
  return static_cast<std::size_t>(std::count_if(face_page.begin(), face_page.end(), [](int page) { return page >= 0; }));
}

Eigen::Vector3f TexturedMesh::AlbedoAt(std::uint32_t face, float b1, float b2) const {
  const int page_index = face_page[face];
  if (page_index < 0) return Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  const cv::Mat& page = pages[page_index];
  const std::array<Eigen::Vector2f, 3>& corners = face_corner_texels[face];
  const Eigen::Vector2f texel = (1.0f - b1 - b2) * corners[0] + b1 * corners[1] + b2 * corners[2];
  const float x = texel.x() - 0.5f, y = texel.y() - 0.5f;
  const int col0 = static_cast<int>(std::floor(x)), row0 = static_cast<int>(std::floor(y));
  const float fx = x - float(col0), fy = y - float(row0);
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (int dr = 0; dr <= 1; ++dr) {
    for (int dc = 0; dc <= 1; ++dc) {
      const int col = std::clamp(col0 + dc, 0, page.cols - 1), row = std::clamp(row0 + dr, 0, page.rows - 1);
      const cv::Vec3f& value = page.at<cv::Vec3f>(row, col);
      sum += (dc ? fx : 1.0f - fx) * (dr ? fy : 1.0f - fy) * Eigen::Vector3f(value[0], value[1], value[2]);
    }
  }
  return sum;
}

}  // namespace lutex
