#include "texturing/texture_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lib/raycast/raycast_scene.h"
#include "lib/util/parallel_for.h"
#include "texturing/face_adjacency.h"
#include "texturing/view_selection.h"

namespace lutex {

TexturedMesh HalveTexture(const TexturedMesh& textured) {
  TexturedMesh halved;
  halved.mesh = textured.mesh;
  halved.face_page = textured.face_page;
  halved.up = textured.up;
  halved.georeference = textured.georeference;
  for (const cv::Mat& page : textured.pages) {
    cv::Mat even;
    cv::copyMakeBorder(page, even, 0, page.rows % 2, 0, page.cols % 2, cv::BORDER_REPLICATE);
    cv::Mat half;
    cv::resize(even, half, cv::Size(even.cols / 2, even.rows / 2), 0.0, 0.0, cv::INTER_AREA);
    halved.pages.push_back(half);
  }
  halved.face_corner_texels = textured.face_corner_texels;
  for (std::array<Eigen::Vector2f, 3>& corners : halved.face_corner_texels) {
    for (Eigen::Vector2f& corner : corners) corner *= 0.5f;
  }
  return halved;
}

namespace {

// The fine parts as one ray-casting scene, and where each part's faces start in it.
class FineSurface {
 public:
  explicit FineSurface(const std::vector<TransferSource>& parts) : parts_(parts), scene_(Concatenate(parts, offsets_)) {}

  struct Point {
    std::size_t part = 0;
    std::uint32_t face = 0;
    float b1 = 0.0f, b2 = 0.0f;
  };

  // The fine surface point nearest to `point` along the line through it in `direction` (unit), within
  // `reach` on either side; false when there is none.
  bool Find(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double reach, Point* found) const {
    double best = std::numeric_limits<double>::infinity();
    for (const double side : {1.0, -1.0}) {
      const RayHit hit = scene_.Intersect(point + side * reach * direction, -side * direction);
      if (!hit.hit || hit.distance > 2.0 * reach) continue;
      const double offset = std::abs(hit.distance - reach);
      if (offset >= best) continue;
      best = offset;
      const auto next = std::upper_bound(offsets_.begin(), offsets_.end(), static_cast<std::size_t>(hit.face_id));
      found->part = static_cast<std::size_t>(next - offsets_.begin()) - 1;
      found->face = static_cast<std::uint32_t>(static_cast<std::size_t>(hit.face_id) - offsets_[found->part]);
      found->b1 = hit.b1;
      found->b2 = hit.b2;
    }
    return best < std::numeric_limits<double>::infinity();
  }

  std::uint32_t ViewOf(const Point& point) const { return (*parts_[point.part].view_of_face)[point.face]; }
  Eigen::Vector3f AlbedoAt(const Point& point) const {
    return parts_[point.part].textured->AlbedoAt(point.face, point.b1, point.b2);
  }

 private:
  static Mesh Concatenate(const std::vector<TransferSource>& parts, std::vector<std::size_t>& offsets) {
    Mesh all;
    for (const TransferSource& part : parts) {
      const Mesh& mesh = part.textured->mesh;
      offsets.push_back(all.faces.size());
      const auto first_vertex = static_cast<std::uint32_t>(all.vertices.size());
      all.vertices.insert(all.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
      for (const Mesh::Face& face : mesh.faces) {
        all.faces.push_back({face[0] + first_vertex, face[1] + first_vertex, face[2] + first_vertex});
      }
    }
    return all;
  }

  const std::vector<TransferSource>& parts_;
  std::vector<std::size_t> offsets_;
  RaycastScene scene_;
};

Eigen::Vector3d UnitNormal(const Mesh& mesh, std::size_t face) {
  const Mesh::Face& f = mesh.faces[face];
  const Eigen::Vector3d normal =
      (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
  const double length = normal.norm();
  return length > 0.0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d SurfacePoint(const Mesh& mesh, std::size_t face, double b1, double b2) {
  const Mesh::Face& f = mesh.faces[face];
  return (1.0 - b1 - b2) * mesh.vertices[f[0]] + b1 * mesh.vertices[f[1]] + b2 * mesh.vertices[f[2]];
}

}  // namespace

TransferredTexture TransferTexture(const std::vector<TransferSource>& fine, const Mesh& coarse,
                                   const std::vector<TextureView>& views, double search_distance,
                                   const TextureBakingOptions& options) {
  if (!(search_distance > 0.0)) throw std::invalid_argument("texture transfer: the search distance must be positive");
  bool any_textured = false;
  for (const TransferSource& part : fine) {
    if (part.textured == nullptr || part.view_of_face == nullptr ||
        part.view_of_face->size() != part.textured->mesh.faces.size() ||
        part.textured->face_page.size() != part.textured->mesh.faces.size()) {
      throw std::invalid_argument("texture transfer: a fine part without its texture or with labels of another length");
    }
    any_textured = any_textured || part.textured->NumTexturedFaces() > 0;
  }
  TransferredTexture result;
  result.textured.mesh = coarse;
  result.view_of_face.assign(coarse.faces.size(), kNoView);
  if (!any_textured) {
    result.textured.face_page.assign(coarse.faces.size(), -1);
    result.textured.face_corner_texels.assign(coarse.faces.size(), {});
    return result;
  }
  const FineSurface surface(fine);

  // Labels: the view of the fine face under the centre, or else under a point nearer a corner.
  ParallelFor(coarse.faces.size(), options.num_threads, [&](std::size_t f) {
    const Eigen::Vector3d normal = UnitNormal(coarse, f);
    if (normal.isZero()) return;
    constexpr double kThird = 1.0 / 3.0, kNearCorner = 1.0 / 6.0;
    const double probes[4][2] = {{kThird, kThird}, {kNearCorner, kNearCorner}, {4.0 * kNearCorner, kNearCorner},
                                 {kNearCorner, 4.0 * kNearCorner}};
    for (const auto& probe : probes) {
      FineSurface::Point point;
      if (!surface.Find(SurfacePoint(coarse, f, probe[0], probe[1]), normal, search_distance, &point)) continue;
      const std::uint32_t view = surface.ViewOf(point);
      if (view == kNoView) continue;
      result.view_of_face[f] = view;
      return;
    }
  });

  // Colours: each texel shows the fine texture at its surface point's counterpart.
  const TexelColouring sample = [&](const TexelLayout& layout, std::size_t, std::size_t, std::vector<cv::Mat>& pages) {
    constexpr std::size_t kChunk = 4096;
    const std::size_t num_chunks = (layout.texels.size() + kChunk - 1) / kChunk;
    ParallelFor(num_chunks, options.num_threads, [&](std::size_t chunk) {
      const std::size_t end = std::min(layout.texels.size(), (chunk + 1) * kChunk);
      for (std::size_t t = chunk * kChunk; t < end; ++t) {
        const AtlasTexel& texel = layout.texels[t];
        const Eigen::Vector3d normal = UnitNormal(coarse, texel.face);
        FineSurface::Point point;
        if (normal.isZero() ||
            !surface.Find(SurfacePoint(coarse, texel.face, texel.b1, texel.b2), normal, search_distance, &point)) {
          continue;
        }
        const Eigen::Vector3f albedo = surface.AlbedoAt(point);
        if (!albedo.allFinite()) continue;
        pages[texel.page].at<cv::Vec3f>(texel.y, texel.x) = cv::Vec3f(albedo.x(), albedo.y(), albedo.z());
      }
    });
  };
  const FaceAdjacency adjacency(coarse);
  TextureBakingSummary summary;
  BakeLabelledFaces(coarse, adjacency, views, result.view_of_face, options, /*show_progress=*/false, sample,
                    result.textured, summary);
  return result;
}

}  // namespace lutex
