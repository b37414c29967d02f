// The mesh on disk tile by tile (texturing/tiled_mesh_file.h): any set of tiles reads back as the piece
// ExtractTileMesh cuts from the mesh itself, at coordinates of a UTM-sized survey, bit for bit, with the
// labels written to its faces since.

#include "texturing/tiled_mesh_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <utility>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

// A wavy floor at UTM-sized coordinates (double precision matters), its faces shuffled among five tiles
// so that a tile's faces are not a run of indices and most vertices are shared between tiles.
struct Scene {
  Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.2 * std::sin(3.0 * x) * y + 1e-7 * x + 812.5; },
                                  500123.0, 500125.0, 6001234.0, 6001235.5, 23, 17);
  std::vector<std::vector<std::uint32_t>> tiles{5};

  Scene() {
    std::mt19937 random(11);
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) tiles[random() % tiles.size()].push_back(f);
  }
  std::vector<const std::vector<std::uint32_t>*> TileList() const {
    std::vector<const std::vector<std::uint32_t>*> list;
    for (const std::vector<std::uint32_t>& tile : tiles) list.push_back(&tile);
    return list;
  }
};

Eigen::AlignedBox3d FaceBox(const Mesh& mesh, std::uint32_t face) {
  Eigen::AlignedBox3d box;
  for (std::uint32_t v : mesh.faces[face]) box.extend(mesh.vertices[v]);
  return box;
}

TEST(TiledMeshFile, ReadsBackThePieceCutFromTheMesh) {
  const Scene scene;
  const testing::TempDir dir;
  const TiledMeshFile file(scene.mesh, scene.TileList(), dir.path() / "mesh");  // labels unset: all ones
  ASSERT_EQ(file.num_tiles(), 5u);
  EXPECT_EQ(file.num_faces(), scene.mesh.faces.size());
  for (std::size_t t = 0; t < scene.tiles.size(); ++t) {
    Eigen::AlignedBox3d expected;
    for (std::uint32_t f : scene.tiles[t]) expected.extend(FaceBox(scene.mesh, f));
    EXPECT_TRUE(file.box(t).isApprox(expected)) << "tile " << t;
  }
  // Tiles 3, 0 and 4 (in that order); of tile 0 only the faces in a box, of the others all.
  const Eigen::AlignedBox3d window(Eigen::Vector3d(500123.5, 6001234.2, 0.0), Eigen::Vector3d(500124.1, 6001234.9, 1e3));
  const TiledMeshFile::Piece piece = file.Read({3, 0, 4}, [&](std::size_t tile, const Eigen::AlignedBox3d& face_box) {
    return tile != 0 || face_box.intersects(window);
  });
  std::vector<std::uint32_t> faces, tile_of_face(scene.mesh.faces.size(), 99);
  for (std::size_t t : {3, 0, 4}) {
    for (std::uint32_t f : scene.tiles[t]) {
      tile_of_face[f] = static_cast<std::uint32_t>(t);
      if (t != 0 || FaceBox(scene.mesh, f).intersects(window)) faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  ASSERT_GT(faces.size(), 100u);
  ASSERT_LT(faces.size(), scene.mesh.faces.size() / 2 + 100) << "the window must leave out part of tile 0";
  const TileMesh expected = ExtractTileMesh(scene.mesh, faces);
  EXPECT_EQ(piece.mesh_face, faces);
  EXPECT_EQ(piece.tile_mesh.source_vertex, expected.source_vertex);
  EXPECT_EQ(piece.tile_mesh.mesh.faces, expected.mesh.faces);
  ASSERT_EQ(piece.tile_mesh.mesh.vertices.size(), expected.mesh.vertices.size());
  for (std::size_t v = 0; v < expected.mesh.vertices.size(); ++v) {
    ASSERT_EQ(piece.tile_mesh.mesh.vertices[v], expected.mesh.vertices[v]) << "vertex " << v << ", bit for bit";
  }
  ASSERT_EQ(piece.tile.size(), faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) EXPECT_EQ(piece.tile[i], tile_of_face[faces[i]]);
  EXPECT_EQ(piece.label, std::vector<std::uint32_t>(faces.size(), 0xffffffffu));

  // Nothing kept, nothing read.
  const TiledMeshFile::Piece none = file.Read({1, 2}, [](std::size_t, const Eigen::AlignedBox3d&) { return false; });
  EXPECT_TRUE(none.mesh_face.empty());
  EXPECT_TRUE(none.tile_mesh.mesh.vertices.empty());
}

TEST(TiledMeshFile, KeepsEachFacesLabelOnDiskUntilItIsRewritten) {
  const Scene scene;
  const testing::TempDir dir;
  constexpr std::uint32_t kUnset = 77;
  TiledMeshFile file(scene.mesh, scene.TileList(), dir.path() / "mesh", kUnset);
  std::vector<std::uint32_t> tile_of_face(scene.mesh.faces.size());
  for (std::uint32_t t = 0; t < scene.tiles.size(); ++t) {
    for (std::uint32_t f : scene.tiles[t]) tile_of_face[f] = t;
  }
  // Every third face of the mesh labelled, across all tiles and in descending order; then some of them again.
  std::vector<std::uint32_t> expected(scene.mesh.faces.size(), kUnset);
  const auto label = [&](const std::vector<std::uint32_t>& faces, std::uint32_t base) {
    std::vector<std::uint32_t> tiles, labels;
    for (std::uint32_t f : faces) {
      tiles.push_back(tile_of_face[f]);
      labels.push_back(base + f);
      expected[f] = base + f;
    }
    file.SetLabels(faces, tiles, labels);
  };
  std::vector<std::uint32_t> every_third, every_ninth;
  for (std::uint32_t f = static_cast<std::uint32_t>(scene.mesh.faces.size()); f-- > 0;) {
    if (f % 3 == 0) every_third.push_back(f);
    if (f % 9 == 0) every_ninth.push_back(f);
  }
  label(every_third, 1000);
  label(every_ninth, 5000);
  const TiledMeshFile::Piece piece =
      file.Read({4, 2, 0, 1, 3}, [](std::size_t, const Eigen::AlignedBox3d&) { return true; });
  ASSERT_EQ(piece.label.size(), scene.mesh.faces.size());
  for (std::size_t i = 0; i < piece.label.size(); ++i) {
    ASSERT_EQ(piece.label[i], expected[piece.mesh_face[i]]) << "face " << piece.mesh_face[i];
  }
  // The rest of the file is untouched: the piece is still the one cut from the mesh, bit for bit.
  std::vector<std::uint32_t> all(scene.mesh.faces.size());
  for (std::uint32_t f = 0; f < all.size(); ++f) all[f] = f;
  const TileMesh whole = ExtractTileMesh(scene.mesh, all);
  EXPECT_EQ(piece.tile_mesh.mesh.faces, whole.mesh.faces);
  EXPECT_EQ(piece.tile_mesh.source_vertex, whole.source_vertex);
  EXPECT_TRUE(piece.tile_mesh.mesh.vertices == whole.mesh.vertices);

  const std::uint32_t face = scene.tiles[1].front();
  file.SetLabels({face, scene.tiles[0].front(), face}, {1, 0, 1}, {3, 4, 5});
  const TiledMeshFile::Piece tile_1 = file.Read({1}, [](std::size_t, const Eigen::AlignedBox3d&) { return true; });
  ASSERT_EQ(tile_1.mesh_face.front(), face);
  EXPECT_EQ(tile_1.label.front(), 5u) << "a face given twice gets the later label";
  EXPECT_THROW(file.SetLabels({face}, {2}, {9}), std::invalid_argument) << "not in that tile";
  EXPECT_THROW(file.SetLabels({face}, {5}, {9}), std::invalid_argument) << "no such tile";
  EXPECT_THROW(file.SetLabels({face}, {1}, {}), std::invalid_argument) << "no label";
}

TEST(TiledMeshFile, IsScratchUnderATemporaryNameRemovedWithIt) {
  const Scene scene;
  const testing::TempDir dir;
  {
    const TiledMeshFile file(scene.mesh, scene.TileList(), dir.path() / "mesh");
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      ++files;
      EXPECT_NE(entry.path().filename(), "mesh") << "written under a temporary name";
      EXPECT_GT(entry.file_size(), 20 * scene.mesh.faces.size());
    }
    EXPECT_EQ(files, 1u);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "removed when the file is destroyed";
}

TEST(TiledMeshFile, RefusesTilesThatDoNotHoldEachFaceOnceInAscendingOrder) {
  Scene scene;
  const testing::TempDir dir;
  scene.tiles[1].push_back(scene.tiles[0].front());  // twice
  std::sort(scene.tiles[1].begin(), scene.tiles[1].end());
  EXPECT_THROW(TiledMeshFile(scene.mesh, scene.TileList(), dir.path() / "twice"), std::invalid_argument);
  Scene missing;
  missing.tiles[2].pop_back();
  EXPECT_THROW(TiledMeshFile(missing.mesh, missing.TileList(), dir.path() / "missing"), std::invalid_argument);
  Scene beyond;
  beyond.tiles[3].push_back(static_cast<std::uint32_t>(beyond.mesh.faces.size()));
  EXPECT_THROW(TiledMeshFile(beyond.mesh, beyond.TileList(), dir.path() / "beyond"), std::invalid_argument);
  Scene unsorted;
  std::swap(unsorted.tiles[4][0], unsorted.tiles[4][1]);
  EXPECT_THROW(TiledMeshFile(unsorted.mesh, unsorted.TileList(), dir.path() / "unsorted"), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "a refused file leaves nothing";
}

}  // namespace
}  // namespace lutex
