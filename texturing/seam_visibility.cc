#include "texturing/seam_visibility.h"

#include <algorithm>
#include <array>

namespace lutex {

namespace {

// Barycentric coordinates (b1, b2) of the point `t` along the edge from corner i to corner j of
// `face`, moved towards the third corner by one texel (at most half way).
Eigen::Vector2f PointBesideEdge(const TexturedMesh& textured, std::uint32_t face, int i, int j, float t) {
  const int opposite = 3 - i - j;
  const std::array<Eigen::Vector2f, 3>& texels = textured.face_corner_texels[face];
  const Eigen::Vector2f on_edge = (1.0f - t) * texels[i] + t * texels[j];
  const float distance = (texels[opposite] - on_edge).norm();
  const float s = distance > 0.0f ? std::min(0.5f, 1.0f / distance) : 0.0f;
  std::array<float, 3> b{0.0f, 0.0f, 0.0f};
  b[i] = (1.0f - s) * (1.0f - t);
  b[j] = (1.0f - s) * t;
  b[opposite] = s;
  return {b[1], b[2]};
}

}  // namespace

SeamVisibility MeasureSeamVisibility(const TexturedMesh& textured, const FaceAdjacency& adjacency) {
  const Mesh& mesh = textured.mesh;
  SeamVisibility result;
  double seam_sum = 0.0, interior_sum = 0.0;
  std::size_t seam_samples = 0, interior_samples = 0;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (textured.face_page[f] < 0) continue;
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      const std::uint32_t g = *n;
      if (g < f || textured.face_page[g] < 0) continue;
      // The shared edge: corners (i, j) of f are the same vertices as corners (k, l) of g.
      int corners_f[2], corners_g[2], shared = 0;
      for (int i = 0; i < 3 && shared < 2; ++i) {
        for (int k = 0; k < 3; ++k) {
          if (mesh.faces[f][i] == mesh.faces[g][k]) {
            corners_f[shared] = i;
            corners_g[shared] = k;
            ++shared;
            break;
          }
        }
      }
      if (shared < 2) continue;
      const bool seam = textured.face_page[f] != textured.face_page[g] ||
                        textured.face_corner_texels[f][corners_f[0]] != textured.face_corner_texels[g][corners_g[0]] ||
                        textured.face_corner_texels[f][corners_f[1]] != textured.face_corner_texels[g][corners_g[1]];
      if (seam) ++result.num_seam_edges;
      for (const float t : {0.25f, 0.5f, 0.75f}) {
        const Eigen::Vector2f in_f = PointBesideEdge(textured, f, corners_f[0], corners_f[1], t);
        const Eigen::Vector2f in_g = PointBesideEdge(textured, g, corners_g[0], corners_g[1], t);
        const double step =
            (textured.AlbedoAt(f, in_f.x(), in_f.y()) - textured.AlbedoAt(g, in_g.x(), in_g.y())).cwiseAbs().mean();
        (seam ? seam_sum : interior_sum) += step;
        ++(seam ? seam_samples : interior_samples);
      }
    }
  }
  result.seam_step = seam_samples ? seam_sum / double(seam_samples) : 0.0;
  result.interior_step = interior_samples ? interior_sum / double(interior_samples) : 0.0;
  return result;
}

}  // namespace lutex
