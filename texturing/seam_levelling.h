#pragma once

// Seam levelling (after Lempitsky & Ivanov, "Seamless mosaicing of image-based texture maps", 2007): a
// smooth additive colour correction per (vertex, view) that makes the texture continuous where charts
// of different views meet, while changing each chart as little and as smoothly as possible.
//
// Where two faces chosen from views a and b share an edge (p, q), the colours each side shows are
// sampled at points x = (1 - t) p + t q of the edge, t = 1/4, 1/2, 3/4: each through its own face, by the
// same fusion as its texels (texel_fusion.h: the face's candidate views, depth test, weights, outlier
// rejection, or the chosen view alone with TexelBlend::kSingle). One pass over the views that see those
// faces. The unknowns g(v, a), one per vertex and view of the faces around it, minimise
//
//   sum over seam points   w_x |c_a(x) + (1 - t) g(p, a) + t g(q, a) - c_b(x) - (1 - t) g(p, b) - t g(q, b)|^2
//   + smoothness x sum over the edges (i, j) of every face of view a   |g(i, a) - g(j, a)|^2
//   + fade x sum |g|^2
//
// per channel, by conjugate gradients on the normal equations (diagonal preconditioner, from 0; the
// matrix is never formed: seam_levelling_system.h).
// The seam weights w_x are Cauchy weights of each point's remaining step (three rounds of reweighting,
// scale 1.4826 x the median step, at least 0.002): a step that texture detail, a particle or a
// misregistration makes at one point is not spread into the charts.
//
// With fade = 0 this is Lempitsky's global levelling: a chart between seams is bent as a whole towards
// its neighbours. That is right when views differ by a constant (an exposure); restored images differ
// locally (their error depends on range and on the place in the image), and on the Blender seafloor the
// global form moved the texture away from the true albedo (one view per face: 2.40 -> 3.04 pp) while
// the default fade, which lets a correction die out over a few edges (sqrt(smoothness / fade) ~ 3)
// beside the seam, brought it closer (2.32 pp) and removed as much of the seams.
//
// A texel of a face of view a then adds the barycentric mix of g(corner, a). The corrections are the
// whole mesh's, so the tiles of a tiled bake, which keep the views chosen for the whole mesh, are
// levelled alike and their borders stay seamless; the orthomosaic's cells get the same corrections.
//
// Only the vertices within 4 fade lengths of a seam (in edges) get unknowns: beyond, a correction would
// be below e^-4 of the seam's, and it is 0. Memory: the chart edges between unknowns (about 3 of 9 bytes
// an unknown, and 8 bytes a face edge while they are gathered), the seam points (3 per seam edge) and a
// byte per vertex; time: one pass over the views plus the solves (single-threaded, so the result does not
// depend on the thread count).

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/mesh.h"
#include "texturing/face_adjacency.h"
#include "texturing/face_view_candidates.h"
#include "texturing/texel_fusion.h"
#include "texturing/texel_layout.h"
#include "texturing/texture_views.h"

namespace lutex {

struct SeamLevellingOptions {
  bool enabled = true;
  // Weight of the corrections' smoothness within a chart against continuity at the seams (per point).
  double smoothness = 0.1;
  // Weight pulling every correction towards 0 (see above); 0: global levelling.
  double fade = 0.01;
  int max_iterations = 1000;
  void Check() const;
};

struct SeamLevellingSummary {
  bool enabled = false;
  std::size_t num_seam_points = 0;  // seam points seen from both sides
  std::size_t num_unknowns = 0;     // (vertex, view) pairs near the seams
  int iterations = 0;               // conjugate-gradient iterations, the most over the channels
  double step_before = 0.0;         // mean |c_a - c_b| over seam points and channels, linear albedo
  double step_after = 0.0;          // the same with the corrections
  double seconds = 0.0;
};

// A part of a larger mesh levelled piece by piece (one tile of a tiled bake, with the surface around it):
// the faces levelled here, and what the pieces levelled before settled. The seam points with a side here
// are levelled; a correction (vertex, view) that a face levelled before also has is held at the value it
// settled there (0 when it had none), so that the piece's border shows the same corrections from both
// sides. The faces of pieces not levelled yet have no label (kNoView) here. A face levelled before that the
// caller shows with this piece's corrections (a mosaic's cell on it) holds the settled ones at all its
// corners, not only where it meets a face here.
struct SeamLevellingPart {
  std::vector<bool> levelled_here;  // one per face of the mesh
  std::vector<bool> shown;          // one per face of the mesh, or empty: none
  std::function<Eigen::Vector3f(std::uint32_t vertex, std::uint32_t view)> settled;
};

// The corrections, by vertex and view; zero for pairs that have none.
class SeamCorrections {
 public:
  bool empty() const { return values_.empty(); }
  Eigen::Vector3f At(std::uint32_t vertex, std::uint32_t view) const;
  // The views with a correction at `vertex`, and the corrections, appended to `out`.
  void AppendAt(std::uint32_t vertex, std::vector<std::pair<std::uint32_t, Eigen::Vector3f>>* out) const;

 private:
  friend SeamCorrections LevelSeams(const Mesh&, const FaceAdjacency&, const std::vector<TextureView>&,
                                    const ViewRaycaster&, const ViewImageSource&, const FaceViewCandidates&,
                                    const std::vector<std::uint32_t>&, const TexelFusionOptions&,
                                    const SeamLevellingOptions&, SeamLevellingSummary*, const SeamLevellingPart*);
  // The views of the faces around vertex v: views_[offsets_[v] .. offsets_[v + 1]), ascending; values_ alike.
  std::vector<std::uint32_t> offsets_;
  std::vector<std::uint32_t> views_;
  std::vector<Eigen::Vector3f> values_;
};

// One line for a summary: "off", "no seams", or the step before and after, the size and the time.
std::string DescribeSeamLevelling(const SeamLevellingSummary& summary);

// `view_of_face`: the chosen view of every face of `mesh` (kNoView: untextured). Empty corrections when
// options.enabled is false or there is no seam. `part`: null for a whole mesh. Throws what the image
// source throws.
SeamCorrections LevelSeams(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                           const ViewRaycaster& raycaster, const ViewImageSource& source,
                           const FaceViewCandidates& candidates, const std::vector<std::uint32_t>& view_of_face,
                           const TexelFusionOptions& fusion, const SeamLevellingOptions& options,
                           SeamLevellingSummary* summary, const SeamLevellingPart* part = nullptr);

// Adds the corrections to fused texels (`pages` as FuseTexels writes them): each texel of a face gets the
// barycentric mix of its corners' corrections for the face's view, clamped at 0; texels without colour
// (NaN) stay so. `mesh` and `view_of_face` are those of the layout; `source_vertex` gives the index, in
// the mesh the corrections were solved on, of each vertex of `mesh` (empty: the same mesh).
void ApplySeamCorrections(const Mesh& mesh, const std::vector<std::uint32_t>& view_of_face,
                          const SeamCorrections& corrections, const std::vector<std::uint32_t>& source_vertex,
                          const TexelLayout& layout, int num_threads, std::vector<cv::Mat>& pages);

}  // namespace lutex
