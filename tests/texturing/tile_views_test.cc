// The views of a tiled bake chosen tile by tile on each tile's piece of the mesh (texturing/tile_views.h),
// against the same choice over the whole mesh: a seafloor with a boulder that hides floor of other tiles
// from the oblique views, split into four tiles that meet near the boulder.

#include "texturing/tile_views.h"

#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/rendered_views.h"
#include "tests/support/temp_dir.h"
#include "texturing/face_adjacency.h"
#include "texturing/view_selection.h"

namespace lutex {
namespace {

// The boulder floor (rendered_views.h) seen by nine cameras of 320 x 240 from 1.5 m, each image of the
// patchwork a few percent too bright or too dark (as restored images of a dive disagree).
struct Scene {
  Mesh mesh = BoulderFloor();
  std::vector<TextureView> views = NineViewsOfTheCentre(Camera::Pinhole(1, 320, 240, 250.0, 250.0));
  std::vector<std::vector<std::uint32_t>> tiles{4};  // quadrants around (0.25, 0.1), by face centroid
  std::vector<cv::Mat> images;
  ViewImageSource source;

  Scene() {
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (std::uint32_t v : mesh.faces[f]) centroid += mesh.vertices[v] / 3.0;
      tiles[(centroid.x() >= 0.25 ? 1 : 0) + (centroid.y() >= 0.1 ? 2 : 0)].push_back(f);
    }
    const RaycastScene scene(mesh);
    for (std::size_t v = 0; v < views.size(); ++v) {
      images.push_back(RenderPatchwork(scene, views[v]) * (1.0 + 0.12 * std::sin(2.0 * double(v) + 0.5)));
    }
    source.linear_rgb = [this](std::size_t v, const cv::Rect& window) { return ViewWindow(images[v], window); };
  }

  std::vector<const std::vector<std::uint32_t>*> TileList() const {
    return {&tiles[0], &tiles[1], &tiles[2], &tiles[3]};
  }
};

std::vector<std::uint32_t> ViewsOf(const FaceViewCandidates& candidates, std::uint32_t face) {
  return std::vector<std::uint32_t>(candidates.Views(face), candidates.Views(face) + candidates.NumViews(face));
}

// Each tile's piece holds what hides its faces: their candidate views are those the whole mesh gives.
// Without the rest of the mesh around it, a tile would see floor that the boulder hides.
TEST(TiledViewChoice, EachTilesPieceFindsTheCandidatesOfTheWholeMesh) {
  const Scene scene;
  TextureBakingOptions options;
  options.levelling.enabled = false;
  const FaceAdjacency adjacency(scene.mesh);
  const RaycastScene whole_scene(scene.mesh);
  const FaceViewCandidates whole = FindFaceViewCandidates(scene.mesh, adjacency, scene.views,
                                                          ViewRaycaster(whole_scene), scene.source, options.visibility);
  const testing::TempDir scratch;
  TiledViewChoice choice(scene.mesh, scene.views, scene.TileList(), options, scratch.path() / "mesh");
  std::size_t compared = 0, differ = 0, differ_alone = 0;
  for (std::size_t t = 0; t < scene.tiles.size(); ++t) {
    const TilePiece piece = choice.Choose(t, scene.source);
    ASSERT_EQ(piece.tile_faces.size(), scene.tiles[t].size());
    EXPECT_GT(piece.piece.mesh.faces.size(), piece.tile_faces.size()) << "the surface around the tile";

    // The tile alone, for comparison.
    const TileMesh alone = ExtractTileMesh(scene.mesh, scene.tiles[t]);
    const RaycastScene alone_scene(alone.mesh);
    const FaceViewCandidates alone_candidates =
        FindFaceViewCandidates(alone.mesh, FaceAdjacency(alone.mesh), scene.views, ViewRaycaster(alone_scene),
                               scene.source, options.visibility);
    for (std::size_t i = 0; i < piece.tile_faces.size(); ++i) {
      const std::uint32_t face = scene.tiles[t][i];
      ASSERT_EQ(piece.piece.source_vertex[piece.piece.mesh.faces[piece.tile_faces[i]][0]], scene.mesh.faces[face][0]);
      const std::vector<std::uint32_t> expected = ViewsOf(whole, face);
      ++compared;
      differ += ViewsOf(piece.chosen.candidates, piece.tile_faces[i]) != expected;
      differ_alone += ViewsOf(alone_candidates, static_cast<std::uint32_t>(i)) != expected;
    }
  }
  EXPECT_EQ(compared, scene.mesh.faces.size());
  std::cout << "faces whose candidate views differ from the whole mesh's: " << differ << " with the pieces, "
            << differ_alone << " with each tile alone, of " << compared << "\n";
  EXPECT_LE(differ, compared / 200) << "ray hits on the edges between faces may go either way";
  EXPECT_GT(differ_alone, 50u) << "the boulder must hide floor of other tiles for this test to mean anything";
}

// The tiles after the first keep the labels of the tiles before on their faces, and hold the corrections
// those settled at the vertices they share, so a border shows one correction from both sides; the seams
// are levelled as well as over the whole mesh.
TEST(TiledViewChoice, TilesAgreeWithTheTilesBeforeAtTheirBorders) {
  const Scene scene;
  TextureBakingOptions options;
  options.fusion.blend = TexelBlend::kSingle;  // a step at every seam, for the levelling to remove
  const testing::TempDir scratch;
  TiledViewChoice choice(scene.mesh, scene.views, scene.TileList(), options, scratch.path() / "mesh");
  std::vector<std::uint32_t> label(scene.mesh.faces.size(), kChooseView);
  std::map<std::pair<std::uint32_t, std::uint32_t>, Eigen::Vector3f> correction;  // (dive's vertex, view)
  std::size_t fixed_faces = 0, shared_corrections = 0, nonzero_shared = 0;
  for (std::size_t t = 0; t < scene.tiles.size(); ++t) {
    const TilePiece piece = choice.Choose(t, scene.source);
    const Mesh& mesh = piece.piece.mesh;
    std::vector<bool> in_tile(mesh.faces.size(), false);
    for (std::uint32_t i : piece.tile_faces) in_tile[i] = true;
    std::vector<bool> tile_vertex(mesh.vertices.size(), false);
    for (std::uint32_t i : piece.tile_faces) {
      for (std::uint32_t v : mesh.faces[i]) tile_vertex[v] = true;
    }
    // The labels of the faces of tiles before, as those chose them.
    for (std::uint32_t i = 0; i < mesh.faces.size(); ++i) {
      const std::uint32_t label_here = piece.chosen.selection.view_of_face[i];
      // The piece's faces are the dive's in ascending order; find this one by its corners.
      const Mesh::Face corners = {piece.piece.source_vertex[mesh.faces[i][0]], piece.piece.source_vertex[mesh.faces[i][1]],
                                  piece.piece.source_vertex[mesh.faces[i][2]]};
      std::uint32_t face = 0;
      while (scene.mesh.faces[face] != corners) ++face;
      if (in_tile[i]) {
        label[face] = label_here;
      } else if (label[face] != kChooseView) {
        EXPECT_EQ(label_here, label[face]) << "a face of a tile before keeps its label";
        ++fixed_faces;
      } else {
        EXPECT_EQ(label_here, kNoView) << "a face of a tile after is not labelled yet";
      }
    }
    // The corrections at the tile's vertices: where a tile before held one, the same.
    std::vector<std::pair<std::uint32_t, Eigen::Vector3f>> at_vertex;
    for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
      if (!tile_vertex[v]) continue;
      at_vertex.clear();
      piece.chosen.corrections.AppendAt(v, &at_vertex);
      for (const auto& [view, value] : at_vertex) {
        const auto key = std::make_pair(piece.piece.source_vertex[v], view);
        const auto before = correction.find(key);
        if (before != correction.end()) {
          EXPECT_EQ(value, before->second) << "vertex " << key.first << ", view " << view;
          ++shared_corrections;
          nonzero_shared += value.norm() > 1e-4f;
        } else {
          correction[key] = value;
        }
      }
    }
  }
  std::cout << fixed_faces << " faces of tiles before seen with their labels, " << shared_corrections
            << " corrections shared at borders (" << nonzero_shared << " not zero)\n";
  EXPECT_GT(fixed_faces, 20u);
  EXPECT_GT(nonzero_shared, 5u) << "the borders must cross seams for this test to mean anything";

  const SeamLevellingSummary& tiled = choice.levelling();
  const FaceAdjacency adjacency(scene.mesh);
  const RaycastScene whole_scene(scene.mesh);
  const ChosenViews whole = ChooseViews(scene.mesh, adjacency, scene.views, ViewRaycaster(whole_scene), scene.source, options);
  std::cout << "seam steps: tile by tile " << tiled.step_before << " -> " << tiled.step_after << " at "
            << tiled.num_seam_points << " points; whole mesh " << whole.levelling.step_before << " -> "
            << whole.levelling.step_after << " at " << whole.levelling.num_seam_points << "\n";
  EXPECT_GT(tiled.step_before, 0.01);
  EXPECT_LT(tiled.step_after, 0.3 * tiled.step_before);
  EXPECT_LT(tiled.step_after, 1.5 * whole.levelling.step_after + 0.002);
}

}  // namespace
}  // namespace lutex
