#pragma once

// Which views see each face, and how well: the data of the view selection and of the texel fusion.
//
// Visibility is exact: a face is seen by a view when the view's ray-cast face-id map has pixels of that
// face (occlusion by any other part of the mesh is then already accounted for). Faces smaller than a
// pixel may fall between pixel centres; a face next to a seen face counts as seen when the ray through
// its centroid's pixel hits the surface at the centroid's depth.
//
// Where faces are many pixels wide (a 12 MP camera over a mesh of centimetre faces), casting every pixel
// counts each face's pixels far more finely than its quality needs. A view is then cast at every s-th
// pixel in each direction, s the largest (at most kMaxVisibilityStride) that leaves the view's median
// face at least `rays_per_face` rays, and a face no ray hits is judged by its centroid's ray as above.
//
// Quality of a (face, view) pair = projected area of the face in pixels (resolution; it falls with the
// square of the distance and with the cosine of the viewing angle) x fraction of the face that is seen
// x mean confidence of the seen pixels (the restoration's confidence: low in haze, in the dark, where
// saturated and where the LUT was not constrained). Views that see the face more grazing than
// `min_cos_angle` are not candidates. The fraction seen is the rays that hit the face over the rays that
// fall inside its projection (on the ray grid continued beyond the image, so a face the image's edge
// cuts is partly seen): 1 for a face nothing hides, however the pixel grid falls on it. It was the
// pixels hit over the projected area, which scatters by about the face's perimeter over its area (20 %
// at 100 pixels) and made neighbouring faces prefer different views by chance: on the 12 MP benchmark
// (faces of about 32 pixels) 1322 charts, now 398, and 18929 chart-border edges, now 11985, with the
// same accuracy against the true albedo (README, 'Visibility').

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "lib/geometry/mesh.h"
#include "texturing/face_adjacency.h"
#include "texturing/texture_views.h"

namespace lutex {

inline constexpr int kMaxVisibilityStride = 4;

struct FaceViewCandidate {
  std::uint32_t view = 0;
  float quality = 0.0f;
};

struct FaceViewCandidatesOptions {
  // Best views kept per face (memory: 8 bytes per face and view kept, 4 once the views are chosen).
  int max_views_per_face = 8;
  // Views seeing a face at more than acos(min_cos_angle) from its normal are dropped (~80 degrees).
  double min_cos_angle = 0.17;
  // Rays the median face of a view must keep when the view is cast at every s-th pixel (above); 0: every
  // pixel. With 8 the 12 MP benchmark's faces (about 32 pixels) are cast at every 2nd pixel (visibility
  // 16.8 -> 6.9 s, the same texture accuracy); on the Blender seafloor, cast with only 2 - 4 rays a face,
  // the seams widened (0.81 -> 0.99 pp), so fewer than 8 is not the default.
  int rays_per_face = 8;
  // Threads over views; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;
  // Progress and the strides in the log (a tiled bake, which runs a pass per tile, reports its own).
  bool show_progress = true;
  void Check() const;
};

// The s above for `view`: from the median projected area of a sample of the faces in front of it (every
// face of a small mesh, about 4000 of a large one), 1 when `rays_per_face` is 0.
int VisibilityStride(const Mesh& mesh, const TextureView& view, int rays_per_face);

// The candidates of every face, best first (ties: lower view index first): their views and, until
// DropQualities, their qualities, in two tables (4 + 4 bytes a slot).
class FaceViewCandidates {
 public:
  FaceViewCandidates(std::size_t num_faces, int max_views_per_face);

  std::size_t NumFaces() const { return counts_.size(); }
  std::size_t NumViews(std::uint32_t face) const { return counts_[face]; }
  // The NumViews(face) candidate views of `face`, best first.
  const std::uint32_t* Views(std::uint32_t face) const { return views_.data() + face * stride_; }
  // The quality of the i-th candidate of `face`; throws std::logic_error after DropQualities.
  float Quality(std::uint32_t face, std::size_t i) const;

  // Keeps `candidate` when it is among the best of `face`. Not thread-safe for one face.
  void Offer(std::uint32_t face, const FaceViewCandidate& candidate);

  // The candidates of `faces` (each < NumFaces()), as faces 0, 1, ... of a new table, with qualities
  // unless they were dropped.
  FaceViewCandidates Subset(const std::vector<std::uint32_t>& faces) const;

  // Frees the qualities, which only view selection reads: the fusion and the seam levelling need the
  // views alone (at 1.25 M faces and 8 views a face, 40 MB less while the tiles are baked).
  void DropQualities();

 private:
  // Throws std::logic_error when the qualities were dropped (a table of no faces has none to drop).
  void RequireQualities() const;

  std::size_t stride_;
  std::vector<std::uint32_t> views_;
  std::vector<float> qualities_;
  std::vector<std::uint8_t> counts_;
};

// The views a visibility pass casts (indices into the views, ascending) and the stride of every view.
// For a part of a mesh (one tile of a tiled bake, with the surface around it that may hide it) the part's
// views are cast at the strides of the whole mesh, so that the part's faces get the candidates they would
// get in the whole.
struct VisibilityCasts {
  std::vector<std::uint32_t> views;
  std::vector<int> stride_of_view;  // one per view
  // When set, only the faces within this box need candidates: each view is cast over the window its
  // projection covers (with a margin of 3 rays, which a windowed cast renders as the whole image does),
  // or whole when part of the box lies behind the camera.
  std::optional<Eigen::AlignedBox3d> faces_within;
};

// Every view, at the strides VisibilityStride gives on `mesh`.
VisibilityCasts CastEveryView(const Mesh& mesh, const std::vector<TextureView>& views, int rays_per_face);

// Streams every view of `casts` once (ray cast + confidence). Throws what the image source throws.
FaceViewCandidates FindFaceViewCandidates(const Mesh& mesh, const FaceAdjacency& adjacency,
                                          const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                                          const ViewImageSource& source, const FaceViewCandidatesOptions& options,
                                          const VisibilityCasts& casts);
// The same for every view (CastEveryView).
FaceViewCandidates FindFaceViewCandidates(const Mesh& mesh, const FaceAdjacency& adjacency,
                                          const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                                          const ViewImageSource& source, const FaceViewCandidatesOptions& options);

}  // namespace lutex
