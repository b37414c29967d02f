#pragma once

// The views of a tiled bake chosen tile by tile, each on the tile's own piece of the mesh, so that the
// memory and the work of choosing them are those of a tile, not of the dive (`lutex tiles`).
//
// A tile's piece is its faces and every face that may hide them from a view that sees them: the views
// whose frustum reaches the tile's box grown by the mesh's longest edge (so that the faces next to the
// tile's are in it too), and the faces that reach the box around that grown box and those views' centres
// (a ray from a camera to the tile does not leave it). On the piece, with its own ray-casting scene and
// adjacency (texture_baker.h ChooseViews with a ViewChoicePart):
//   1. the candidates of its faces from those views, cast at the strides of the whole mesh over the
//      window of each view the grown box covers (face_view_candidates.h VisibilityCasts), so that a face
//      gets the candidates it gets in the whole;
//   2. the labels of the tile's faces, with the labels of the tiles chosen before fixed (view_selection.h):
//      labels agree across tile borders as they do inside a tile;
//   3. the seam levelling of the tile's faces, with the corrections the tiles before settled held at the
//      vertices they share (seam_levelling.h SeamLevellingPart): a border shows one correction from both
//      sides.
// Kept for the whole dive between tiles: the corrections at the vertices of tile borders in memory, and on
// disk the mesh tile by tile with each face's label (tiled_mesh_file.h), from which each piece is read
// with the labels of the faces chosen before: the mesh and the tiles' face lists the choice is made from
// may be freed once it is constructed. The rest (the piece, its scene, adjacency and candidates) lives as
// long as the tile's bake, which BakeFaces does with the piece's choice.
//
// Tiles are chosen in the order they are asked for, and the result depends on that order (the later of
// two neighbours adapts to the earlier), not on the thread count.
//
// A caller may show, with a tile's choice, faces beyond the tile's (a mosaic's cells show the topmost face
// below them, whichever tile it is in: TileUse). Those not chosen yet are chosen with the tile's; those
// chosen before keep their labels and hold the corrections settled for them at all their corners; and a
// face chosen here that a later tile may show too has its corrections at all its corners settled for it.
// So every face shows one label and one set of corrections, whichever tile shows it.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lib/geometry/mesh.h"
#include "lib/raycast/raycast_scene.h"
#include "texturing/texture_baker.h"
#include "texturing/texture_views.h"
#include "texturing/tile_mesh.h"
#include "texturing/tiled_mesh_file.h"

namespace lutex {

struct TilePiece {
  TileMesh piece;                         // its mesh, and each vertex's index in the dive's mesh
  std::vector<std::uint32_t> tile_faces;  // the piece's faces chosen here, ascending
  std::unique_ptr<RaycastScene> scene;
  std::unique_ptr<ViewRaycaster> raycaster;  // of `scene`, with the choice's ray tables
  ChosenViews chosen;                     // for every face of the piece
};

// What a caller shows with a tile's choice beyond the tile's own faces (piece faces: indices in the piece).
struct TileUse {
  // Given the piece, before the views are chosen: the piece's faces the caller may show, ascending.
  std::function<std::vector<std::uint32_t>(const TileMesh& piece)> shown;
  // Whether a tile chosen later may show this piece face, chosen here, too.
  std::function<bool(std::uint32_t piece_face)> shown_later;
};

class TiledViewChoice {
 public:
  // `tiles`: the faces of each tile, ascending; together each face of `mesh` once. `spans`: one box per
  // tile that the faces it shows lie in besides its own (empty: none). The mesh is written tile by tile
  // beside `scratch`, under a temporary name, until the choice is destroyed; neither `mesh` nor `tiles`
  // is used after the constructor. `views` are referred to and must outlive the choice.
  TiledViewChoice(const Mesh& mesh, const std::vector<TextureView>& views,
                  const std::vector<const std::vector<std::uint32_t>*>& tiles, const TextureBakingOptions& options,
                  const std::filesystem::path& scratch, const std::vector<Eigen::AlignedBox3d>& spans = {});

  // Chooses the views of tile `tile` (each tile once), and of the faces `use` shows that no tile chose
  // before. With no face within the tile's reach, the piece is empty and has no scene. Throws what the
  // image source and `use` throw, and std::runtime_error naming the mesh's scratch file when it cannot be
  // read or written.
  TilePiece Choose(std::size_t tile, const ViewImageSource& source, const TileUse* use = nullptr);

  // Over the tiles chosen so far: the seam levelling (points, corrections and steps summed or averaged
  // by points, iterations the most), and the time of each step.
  const SeamLevellingSummary& levelling() const { return levelling_; }
  double seconds() const { return seconds_; }
  std::size_t max_piece_faces() const { return max_piece_faces_; }

 private:
  // Whether any of `box`'s corners can be in `view`'s image: false when all lie beyond one side of its
  // frustum (conservative: the frustum is the image's border, sampled, grown by a little).
  bool MaySee(std::size_t view, const Eigen::AlignedBox3d& box) const;

  const std::vector<TextureView>& views_;
  TextureBakingOptions options_;
  VisibilityCasts strides_;                     // every view's stride on the whole mesh
  TiledMeshFile mesh_file_;                     // each face labelled kChooseView until its tile is chosen
  std::shared_ptr<ViewRayTables> rays_ = std::make_shared<ViewRayTables>();  // shared by the pieces
  std::vector<Eigen::AlignedBox3d> tile_boxes_;  // of each tile's faces and span
  double longest_edge_ = 0.0;
  // Per view, the image's extent in normalised camera coordinates (x / z, y / z): min x, max x, min y, max y.
  std::vector<Eigen::Vector4d> view_extent_;
  // Corrections at tile borders: (dive's vertex << 32 | view) -> correction.
  std::unordered_map<std::uint64_t, Eigen::Vector3f> settled_;
  SeamLevellingSummary levelling_;
  double seconds_ = 0.0;
  std::size_t max_piece_faces_ = 0;
};

}  // namespace lutex
