#pragma once

// Bakes one albedo texture atlas for a mesh from many posed views (texturing/ in DESIGN.md):
//
//   1. visibility and quality of every (face, view) pair        face_view_candidates.h   (one pass over views)
//   2. one view per face: MRF, loopy belief propagation          view_selection.h
//      and a colour correction per (vertex, view) for the seams   seam_levelling.h         (one pass over views)
//   3. charts of faces with the same view, projected into it     texture_charts.h
//   4. charts packed into atlas pages                            atlas_packing.h
//   5. texels tied to surface points, borders included           texel_layout.h
//   6. texel colours fused from all views that see them,         texel_fusion.h           (passes over views)
//      plus the seam correction
//      (5 and 6 a batch of neighbouring charts at a time,        spatial_batches.h
//      so the texel table and the samples are held for one batch: fusion.memory_limit_bytes bounds both)
//   7. padding and unseen texels filled by pull-push             texture_fill.h
//   8. the colour step across chart borders, for the summary     seam_visibility.h
//
// Images are loaded on demand through the ViewImageSource, at most one per thread, so memory depends on
// the mesh, the atlas pages and the fusion's limit, not on the number of views.

#include <functional>
#include <string>
#include <vector>

#include "lib/geometry/mesh.h"
#include "lib/raycast/raycast_scene.h"
#include "texturing/face_view_candidates.h"
#include "texturing/seam_levelling.h"
#include "texturing/seam_visibility.h"
#include "texturing/texel_fusion.h"
#include "texturing/texel_layout.h"
#include "texturing/texture_charts.h"
#include "texturing/texture_views.h"
#include "texturing/textured_mesh.h"
#include "texturing/view_selection.h"

namespace lutex {

struct TextureBakingOptions {
  FaceViewCandidatesOptions visibility;
  ViewSelectionOptions selection;
  TextureChartOptions charts;
  TexelFusionOptions fusion;
  SeamLevellingOptions levelling;
  // Border texels (outside every triangle of a chart) within this distance of a triangle show its
  // nearest point; further padding is filled by pull-push.
  double gutter = 2.0;
  // Most atlas pages the output can hold (a textured PLY holds one); 0: no limit. Checked once the charts
  // are packed, before any colour is fused, and before anything when charts.texel_size bounds the atlas
  // from below (the mesh's area in texels).
  std::size_t max_pages = 0;
  // Why the output holds no more, for the message (e.g. "out.ply is a textured PLY, which holds one page").
  std::string max_pages_reason;
  // Threads for every stage; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;
  void Check() const;
};

struct TextureBakingSummary {
  std::size_t num_views = 0;
  std::size_t num_faces = 0;
  std::size_t num_textured_faces = 0;
  std::size_t num_charts = 0;
  std::size_t num_pages = 0;
  std::size_t num_texels = 0;   // texels tied to the surface
  std::size_t page_texels = 0;  // all texels of all pages
  ViewSelection selection;      // without the per-face labels
  TexelFusionSummary fusion;
  SeamLevellingSummary levelling;
  SeamVisibility seams;
  double seconds_visibility = 0.0;
  double seconds_selection = 0.0;
  double seconds_layout = 0.0;
  double seconds_fusion = 0.0;
};

struct TextureBakingResult {
  TexturedMesh textured;
  // The view each face was textured from (the MRF's choice; kNoView for faces no view sees).
  std::vector<std::uint32_t> view_of_face;
  TextureBakingSummary summary;
};

// Steps 1 and 2 over the whole mesh: the candidate views of every face, the view the MRF chose for it and
// the seam levelling's corrections. A tiled bake chooses once and bakes each tile's faces with BakeFaces,
// so that labels, and the colours fused and levelled from them, agree across tile borders.
struct ChosenViews {
  FaceViewCandidates candidates;  // their views (the qualities are dropped once the views are chosen)
  ViewSelection selection;  // with the per-face labels
  SeamCorrections corrections;
  SeamLevellingSummary levelling;
  double seconds_visibility = 0.0;
  double seconds_selection = 0.0;
};
// A piece of a larger mesh whose views are chosen piece by piece (tile_views.h): the views to cast and
// their strides (face_view_candidates.h VisibilityCasts), each face's given label (view_selection.h
// SelectViews: kChooseView for the faces chosen here, whose seams are levelled here) and the seam
// corrections the pieces before settled, and the faces chosen before that the caller shows with this
// piece's corrections (seam_levelling.h SeamLevellingPart).
struct ViewChoicePart {
  VisibilityCasts casts;
  std::vector<std::uint32_t> given;
  std::vector<bool> shown;  // one per face, or empty: none
  std::function<Eigen::Vector3f(std::uint32_t vertex, std::uint32_t view)> settled;
};
// `part`: null for a whole mesh.
ChosenViews ChooseViews(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                        const ViewRaycaster& raycaster, const ViewImageSource& source,
                        const TextureBakingOptions& options, const ViewChoicePart* part = nullptr);

// Steps 3 to 7 for `faces` of the mesh (ascending, each once) with the views chosen for the whole mesh
// (with `options` as chosen): the result's mesh has only those faces, in that order, and the vertices they
// use in ascending order of their index in `mesh` (`source_vertex` gives it). Memory and work are those of
// the faces; the raycaster is the whole mesh's, so the rest of the surface still occludes. `summary` gets
// the counts and times of these steps. Fusion progress is not shown (a tiled bake reports its own).
TexturedMesh BakeFaces(const Mesh& mesh, const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                       const ViewImageSource& source, const ChosenViews& chosen, const std::vector<std::uint32_t>& faces,
                       const TextureBakingOptions& options, std::vector<std::uint32_t>& source_vertex,
                       TextureBakingSummary& summary);

// Colours one batch of texels of a layout into the atlas pages (texels it leaves NaN are filled by
// pull-push afterwards). `batch` of `num_batches`, for progress messages.
using TexelColouring = std::function<void(const TexelLayout& layout, std::size_t batch, std::size_t num_batches,
                                          std::vector<cv::Mat>& pages)>;

// Steps 3 to 7 for the faces of `mesh` whose label is not kNoView, with the texels' colours from `colour`:
// charts projected into their view at options.charts' texel size, packed into pages, laid out a batch of
// neighbouring charts at a time (options.fusion.memory_limit_bytes bounds a batch), coloured, filled.
// Writes the pages and each face's page and corner texels into `textured`; its mesh is left to the caller.
// BakeTexture and BakeFaces colour with the texel fusion; a tiled bake's coarser levels with their
// children's textures (texture_transfer.h).
void BakeLabelledFaces(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                       const std::vector<std::uint32_t>& view_of_face, const TextureBakingOptions& options,
                       bool show_progress, const TexelColouring& colour, TexturedMesh& textured,
                       TextureBakingSummary& summary);

// Throws std::invalid_argument when the mesh's area at options.charts.texel_size cannot fit in
// options.max_pages pages (nothing when either is 0): the check BakeTexture makes before any work.
void CheckAtlasFits(const Mesh& mesh, const TextureBakingOptions& options);

// Throws std::invalid_argument on bad options or an empty mesh or view list, and what the image source
// throws.
// `scene`: the mesh's ray-casting scene when the caller has one (a loaded dive); the other form builds it.
TextureBakingResult BakeTexture(const Mesh& mesh, const RaycastScene& scene, const std::vector<TextureView>& views,
                                const ViewImageSource& source, const TextureBakingOptions& options);
TextureBakingResult BakeTexture(const Mesh& mesh, const std::vector<TextureView>& views, const ViewImageSource& source,
                                const TextureBakingOptions& options);

}  // namespace lutex
