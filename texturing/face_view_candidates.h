#pragma once

// Which views see each face, and how well: the data of the view selection and of the texel fusion.
//
// Visibility is exact: a face is seen by a view when the view's ray-cast face-id map has pixels of that
// face (occlusion by any other part of the mesh is then already accounted for). Faces smaller than a
// pixel may fall between pixel centres; a face next to a seen face counts as seen when the ray through
// its centroid's pixel hits the surface at the centroid's depth.
//
// Quality of a (face, view) pair = projected area of the face in pixels (resolution; it falls with the
// square of the distance and with the cosine of the viewing angle) x fraction of that area that is not
// occluded x mean confidence of the seen pixels (the restoration's confidence: low in haze, in the dark,
// where saturated and where the LUT was not constrained). Views that see the face more grazing than
// `min_cos_angle` are not candidates.

#include <cstdint>
#include <vector>

#include "lib/geometry/mesh.h"
#include "texturing/face_adjacency.h"
#include "texturing/texture_views.h"

namespace lutex {

struct FaceViewCandidate {
  std::uint32_t view = 0;
  float quality = 0.0f;
};

struct FaceViewCandidatesOptions {
  // Best views kept per face (memory: 8 bytes per face and view kept).
  int max_views_per_face = 8;
  // Views seeing a face at more than acos(min_cos_angle) from its normal are dropped (~80 degrees).
  double min_cos_angle = 0.17;
  // Threads over views; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;
  void Check() const;
};

class FaceViewCandidates {
 public:
  FaceViewCandidates(std::size_t num_faces, int max_views_per_face);

  std::size_t NumFaces() const { return counts_.size(); }
  std::size_t NumViews(std::uint32_t face) const { return counts_[face]; }
  // Candidates of `face`, best first (ties: lower view index first).
  const FaceViewCandidate* begin(std::uint32_t face) const { return slots_.data() + face * stride_; }
  const FaceViewCandidate* end(std::uint32_t face) const { return begin(face) + counts_[face]; }

  // Keeps `candidate` when it is among the best of `face`. Not thread-safe for one face.
  void Offer(std::uint32_t face, const FaceViewCandidate& candidate);

 private:
  std::size_t stride_;
  std::vector<FaceViewCandidate> slots_;
  std::vector<std::uint8_t> counts_;
};

// Streams every view once (ray cast + confidence). Throws what the image source throws.
FaceViewCandidates FindFaceViewCandidates(const Mesh& mesh, const FaceAdjacency& adjacency,
                                          const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                                          const ViewImageSource& source, const FaceViewCandidatesOptions& options);

}  // namespace lutex
