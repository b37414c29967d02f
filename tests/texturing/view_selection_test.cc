#include "texturing/view_selection.h"

#include <random>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"

namespace lutex {
namespace {

// A strip of 2 x 20 triangles: each face has 1 to 3 edge neighbours.
Mesh Strip() {
  return MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 20.0, 0.0, 1.0, 20, 1);
}

TEST(FaceAdjacency, StripFacesShareEdgesWithTheirNeighbours) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  ASSERT_EQ(adjacency.NumFaces(), 40u);
  std::size_t edges = 0;
  for (std::uint32_t f = 0; f < 40; ++f) {
    EXPECT_GE(adjacency.Degree(f), 1u);
    EXPECT_LE(adjacency.Degree(f), 3u);
    edges += adjacency.Degree(f);
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      int shared = 0;
      for (std::uint32_t a : mesh.faces[f]) {
        for (std::uint32_t b : mesh.faces[*n]) shared += a == b;
      }
      EXPECT_EQ(shared, 2);
    }
  }
  // 20 diagonals inside the cells + 19 edges between cells, each counted from both sides.
  EXPECT_EQ(edges, 2u * 39u);
}

// View 0 sees every face with quality 1; view 1 sees faces [first, last) with `quality`.
FaceViewCandidates TwoViews(std::size_t num_faces, std::uint32_t first, std::uint32_t last, float quality) {
  FaceViewCandidates candidates(num_faces, 4);
  for (std::uint32_t f = 0; f < num_faces; ++f) {
    candidates.Offer(f, {0, 1.0f});
    if (f >= first && f < last) candidates.Offer(f, {1, quality});
  }
  return candidates;
}

TEST(ViewSelection, ASlightlyBetterViewOnOneFaceIsNotWorthTwoSeams) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  const FaceViewCandidates candidates = TwoViews(40, 20, 21, 1.2f);  // ln 1.2 = 0.18 < 2 x 0.5
  ViewSelectionOptions options;
  const ViewSelection smooth = SelectViews(candidates, adjacency, options);
  for (std::uint32_t view : smooth.view_of_face) EXPECT_EQ(view, 0u);
  EXPECT_DOUBLE_EQ(smooth.smoothness_cost, 0.0);
  options.smoothness = 0.0;  // no smoothness: every face takes its best view
  const ViewSelection best = SelectViews(candidates, adjacency, options);
  EXPECT_EQ(best.view_of_face[20], 1u);
  EXPECT_EQ(best.view_of_face[19], 0u);
}

TEST(ViewSelection, AMuchBetterViewTakesItsRegionWithOneSeam) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  // View 1 is 100 x better on faces 10..29 (data cost 4 for view 0 there).
  const FaceViewCandidates candidates = TwoViews(40, 10, 30, 100.0f);
  const ViewSelection selection = SelectViews(candidates, adjacency, {});
  for (std::uint32_t f = 0; f < 40; ++f) EXPECT_EQ(selection.view_of_face[f], (f >= 10 && f < 30) ? 1u : 0u) << f;
  EXPECT_DOUBLE_EQ(selection.smoothness_cost, 2 * 0.5);  // two seam edges, at faces 9|10 and 29|30
  EXPECT_LE(selection.data_cost + selection.smoothness_cost,
            selection.best_view_data_cost + selection.best_view_smoothness_cost + 1e-9);
}

TEST(ViewSelection, IsolatedNoisyLabelsAreSmoothedAway) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  FaceViewCandidates candidates(40, 4);
  // Views 0 and 1 are nearly equal everywhere (within 10 %); which is better is noise.
  std::mt19937 random(3);
  std::uniform_real_distribution<float> quality(1.0f, 1.1f);
  for (std::uint32_t f = 0; f < 40; ++f) {
    candidates.Offer(f, {0, quality(random)});
    candidates.Offer(f, {1, quality(random)});
  }
  const ViewSelection selection = SelectViews(candidates, adjacency, {});
  EXPECT_EQ(selection.smoothness_cost, 0.0);  // one view for the whole strip
  EXPECT_LT(selection.data_cost + selection.smoothness_cost,
            selection.best_view_data_cost + selection.best_view_smoothness_cost);
  EXPECT_GT(selection.best_view_smoothness_cost, 5.0);  // the best view per face alone makes many seams
}

TEST(ViewSelection, FacesNoViewSeesStayUnlabelled) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  FaceViewCandidates candidates(40, 4);
  for (std::uint32_t f = 0; f < 20; ++f) candidates.Offer(f, {3, 1.0f});
  const ViewSelection selection = SelectViews(candidates, adjacency, {});
  EXPECT_EQ(selection.view_of_face[5], 3u);
  EXPECT_EQ(selection.view_of_face[25], kNoView);
}

// A 60 x 40 grid of cells (4800 faces) seen by four views. On the left half they are all nearly equal
// (within 15 %, noise): the optimum gives the half one view, whichever. On the right half view 3 is 3 x
// better. So the best labelling has one seam line, down the middle.
FaceViewCandidates HalfEqualHalfClear(const Mesh& mesh) {
  FaceViewCandidates candidates(mesh.faces.size(), 4);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> noise(1.0f, 1.15f);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const double x = (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]).x() / 3.0;
    for (std::uint32_t view = 0; view < 4; ++view) {
      candidates.Offer(f, {view, (x > 30.0 && view == 3 ? 3.0f : 1.0f) * noise(random)});
    }
  }
  return candidates;
}

TEST(ViewSelection, RegionsSolvedOneAfterAnotherAgreeAcrossTheirBorders) {
  const Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 60.0, 0.0, 40.0, 60, 40);
  const FaceAdjacency adjacency(mesh);
  const FaceViewCandidates candidates = HalfEqualHalfClear(mesh);
  const ViewSelection whole = SelectViews(candidates, adjacency, {});
  ASSERT_EQ(whole.num_regions, 1u);
  ViewSelectionOptions options;
  options.max_region_faces = 300;
  const ViewSelection regions = SelectViews(candidates, adjacency, options);
  EXPECT_GE(regions.num_regions, 16u);
  // The seam down the middle crosses 40 cell edges; loopy belief propagation leaves a few more (104 for
  // the whole MRF; 91 in regions). Regions that ignored their solved neighbours would each pick their own
  // view on the left half and add seams along the region borders there (203 such; checked).
  const double whole_seams = whole.smoothness_cost / options.smoothness;
  const double region_seams = regions.smoothness_cost / options.smoothness;
  EXPECT_LE(whole_seams, 150.0);
  EXPECT_LE(region_seams, 1.25 * whole_seams);
  EXPECT_LE(regions.data_cost + regions.smoothness_cost, 1.1 * (whole.data_cost + whole.smoothness_cost));
  std::size_t right_on_view_3 = 0, right = 0;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const double x = (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]).x() / 3.0;
    if (x <= 30.0) continue;
    ++right;
    right_on_view_3 += regions.view_of_face[f] == 3u;
  }
  EXPECT_EQ(right_on_view_3, right);
}

// Given labels (a tile of a tiled bake after its neighbours): faces with a given view keep it and pull
// their free neighbours towards it as a region solved before does; faces given kNoView are left out.
// Faces 20 and 21 see view 1 slightly better (ln 1.2 = 0.18 each): alone they would not be worth two
// seams, but with faces 0..19 given view 1 a single seam at 21 | 22 is cheaper than one at 19 | 20.
TEST(ViewSelection, GivenLabelsStayAndPullTheirNeighbours) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  std::vector<std::uint32_t> given(40, kChooseView);
  for (std::uint32_t f = 0; f < 20; ++f) given[f] = 1;
  given[39] = kNoView;
  const FaceViewCandidates others = TwoViews(40, 20, 22, 1.2f);
  const ViewSelection chosen = SelectViews(others, adjacency, {}, given);
  for (std::uint32_t f = 0; f < 20; ++f) EXPECT_EQ(chosen.view_of_face[f], 1u) << f;
  EXPECT_EQ(chosen.view_of_face[20], 1u);
  EXPECT_EQ(chosen.view_of_face[21], 1u);
  for (std::uint32_t f = 22; f < 39; ++f) EXPECT_EQ(chosen.view_of_face[f], 0u) << f;
  EXPECT_EQ(chosen.view_of_face[39], kNoView);
  // Without the given neighbours, the two faces are not worth the seams.
  const ViewSelection alone = SelectViews(others, adjacency, {});
  EXPECT_EQ(alone.view_of_face[20], 0u);
  EXPECT_EQ(alone.view_of_face[21], 0u);
  EXPECT_THROW(SelectViews(others, adjacency, {}, std::vector<std::uint32_t>(3, kChooseView)), std::invalid_argument);
}

TEST(ViewSelection, ARegionMustHoldAFace) {
  const Mesh mesh = Strip();
  const FaceAdjacency adjacency(mesh);
  ViewSelectionOptions options;
  options.max_region_faces = 0;
  EXPECT_THROW(SelectViews(TwoViews(40, 0, 0, 1.0f), adjacency, options), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
