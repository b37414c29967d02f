// `lutex tiles` on a small simulated survey textured from its true albedo images: the tileset follows
// the 3D Tiles 1.1 rules (checked here, as the CesiumGS validator is not reachable from these machines),
// every content passes the Khronos glTF-Validator, the leaves hold every face of the mesh once with the
// colours of the single-GLB bake, the root transform puts the model's origin where its ENU origin is on
// the globe, and the files do not depend on the thread count.

#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "colmap_integration/stages/simulate_workspace.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "colmap_integration/stages/tiles_workspace.h"
#include "lib/geo/earth_frame.h"
#include "lib/geometry/mesh_io.h"
#include "lib/model/surface_albedo.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/glb_triangles.h"
#include "tests/support/gltf_validator.h"
#include "tests/support/small_survey.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// A 4 x 3 m seafloor (2400 faces) seen by 6 images of 160 x 120, simulated once.
const fs::path& SimulatedSurvey() {
  // A static, not a leaked pointer: each case runs in its own process, and the folder must go with it.
  static const testing::TempDir dir;
  static const bool made = [](const fs::path& root) {
    std::ofstream(root / "scene.json") << testing::SmallSurveyScene().dump(1);
    SimulateOptions simulate;
    simulate.scene = root / "scene.json";
    simulate.output = root / "W";
    SimulateWorkspace(simulate);
    return true;
  }(dir.path());
  (void)made;
  return dir.path();
}

const Eigen::Vector3d kEnuOrigin(54.32, 10.14, -20.0);

TilesOptions OptionsFor(const fs::path& output, int num_threads) {
  TilesOptions options;
  options.workspace = SimulatedSurvey() / "W";
  options.mesh = SimulatedSurvey() / "W" / "scene" / "mesh.ply";
  options.views.images = SimulatedSurvey() / "W" / "ground_truth" / "albedo";
  options.views.image_encoding = ImageEncoding::kLinear16;
  options.output = output;
  options.tree.max_faces = 300;
  options.baking.num_threads = num_threads;
  std::ostringstream origin;
  origin.precision(10);
  origin << kEnuOrigin.x() << "," << kEnuOrigin.y() << "," << kEnuOrigin.z();
  options.georeference.enu_origin = origin.str();
  return options;
}

Eigen::AlignedBox3d BoxOf(const nlohmann::json& tile) {
  const nlohmann::json& box = tile["boundingVolume"]["box"];
  EXPECT_EQ(box.size(), 12u);
  const Eigen::Vector3d centre(box[0], box[1], box[2]);
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < 3; ++k) half[k] += std::abs(double(box[3 + 3 * axis + k]));  // the box's extent along x, y, z
  }
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

struct TileCheck {
  std::size_t tiles = 0;
  std::size_t leaves = 0;
  std::size_t leaf_triangles = 0;
  std::vector<fs::path> leaf_contents;
  std::vector<fs::path> parent_contents;
};

// The 3D Tiles 1.1 rules lutex's tilesets must keep, from `tile` down: a box that contains its children's
// boxes and its content, geometric errors that fall towards the leaves (0 there), content that exists and
// that the glTF-Validator passes.
void CheckTile(const nlohmann::json& tile, const fs::path& folder, double parent_error, TileCheck& check) {
  ++check.tiles;
  ASSERT_TRUE(tile.contains("boundingVolume") && tile["boundingVolume"].contains("box"));
  ASSERT_TRUE(tile.contains("geometricError"));
  const double error = tile["geometricError"];
  EXPECT_GE(error, 0.0);
  EXPECT_LT(error, parent_error);
  const Eigen::AlignedBox3d box = BoxOf(tile);
  const Eigen::Vector3d slack = Eigen::Vector3d::Constant(1e-4);
  const Eigen::AlignedBox3d loose(box.min() - slack, box.max() + slack);
  ASSERT_TRUE(tile.contains("content"));
  const fs::path content = folder / tile["content"]["uri"].get<std::string>();
  ASSERT_TRUE(fs::exists(content)) << content;
  const testing::GltfValidation validation = testing::ValidateGltf(content);
  if (validation.ran) {
    EXPECT_TRUE(validation.valid) << content << "\n" << validation.output;
  }
  const testing::GlbTriangles triangles = testing::ReadGlbTriangles(content);
  for (const Eigen::Vector3d& vertex : triangles.vertices_in_tiles_frame) {
    ASSERT_TRUE(loose.contains(vertex)) << content << ": " << vertex.transpose() << " outside the tile's box";
  }
  if (!tile.contains("children")) {
    EXPECT_EQ(error, 0.0) << "a leaf has nothing finer";
    ++check.leaves;
    check.leaf_triangles += triangles.corners_in_model.size();
    check.leaf_contents.push_back(content);
    return;
  }
  EXPECT_GT(error, 0.0);
  check.parent_contents.push_back(content);
  for (const nlohmann::json& child : tile["children"]) {
    const Eigen::AlignedBox3d child_box = BoxOf(child);
    EXPECT_TRUE(loose.contains(child_box)) << "a child's box sticks out of its parent's";
    CheckTile(child, folder, error, check);
  }
}

// Mean absolute error (percentage points, over channels) of the texture at each textured triangle's
// centroid against `truth_at` (the true albedo for the triangle's corners, or nothing to skip it).
double CentroidAlbedoError(
    const std::vector<fs::path>& glbs,
    const std::function<std::optional<Eigen::Vector3d>(const std::array<Eigen::Vector3d, 3>&)>& truth_at) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const fs::path& glb : glbs) {
    const testing::GlbTriangles triangles = testing::ReadGlbTriangles(glb);
    for (std::size_t t = 0; t < triangles.corners_in_model.size(); ++t) {
      if (!triangles.centroid_albedo[t].allFinite()) continue;
      const std::optional<Eigen::Vector3d> expected = truth_at(triangles.corners_in_model[t]);
      if (!expected) continue;
      sum += (triangles.centroid_albedo[t] - *expected).cwiseAbs().sum();
      count += 3;
    }
  }
  EXPECT_GT(count, 0u);
  return 100.0 * sum / double(std::max<std::size_t>(count, 1));
}

// Triangles that are faces of the mesh: against the true albedo at the face's centroid.
double AlbedoError(const std::vector<fs::path>& glbs, const Mesh& mesh) {
  const SurfaceAlbedo truth = SurfaceAlbedo::FromVertexColors(mesh);
  // Faces by their corners, rounded to 0.1 mm (a GLB stores positions in float).
  const auto key = [](const Eigen::Vector3d& p) {
    return std::make_tuple(std::llround(p.x() * 1e4), std::llround(p.y() * 1e4), std::llround(p.z() * 1e4));
  };
  std::map<std::tuple<long long, long long, long long>, std::uint32_t> vertex_of;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) vertex_of[key(mesh.vertices[v])] = v;
  std::map<std::array<std::uint32_t, 3>, int> face_of;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::array<std::uint32_t, 3> corners = mesh.faces[f];
    std::sort(corners.begin(), corners.end());
    face_of[corners] = static_cast<int>(f);
  }
  return CentroidAlbedoError(glbs, [&](const std::array<Eigen::Vector3d, 3>& triangle) -> std::optional<Eigen::Vector3d> {
    std::array<std::uint32_t, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = vertex_of.at(key(triangle[k]));
    std::sort(corners.begin(), corners.end());
    return truth.At(mesh, face_of.at(corners), 1.0 / 3.0, 1.0 / 3.0);
  });
}

// Simplified triangles, which are not faces of the mesh: against the true albedo of the mesh straight
// below the centroid.
double SurfaceAlbedoError(const std::vector<fs::path>& glbs, const Mesh& mesh) {
  const SurfaceAlbedo truth = SurfaceAlbedo::FromVertexColors(mesh);
  const RaycastScene surface(mesh);
  return CentroidAlbedoError(glbs, [&](const std::array<Eigen::Vector3d, 3>& corners) -> std::optional<Eigen::Vector3d> {
    const Eigen::Vector3d centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
    const RayHit hit = surface.Intersect(centroid + Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ());
    if (!hit.hit) return std::nullopt;
    return truth.At(mesh, hit.face_id, hit.b1, hit.b2);
  });
}

// The colour step (percentage points, mean over channels) across every edge that two textured leaf
// triangles share: each side sampled through its own tile's texture at a quarter, half and three quarters
// along the edge, a tenth of the way towards its opposite corner. Edges between two leaves (tile borders)
// apart from edges inside one leaf (whose steps are the texture's own detail, and its chart borders).
struct EdgeSteps {
  double tile_borders = 0.0, inside_tiles = 0.0;
  std::size_t border_edges = 0, inside_edges = 0;
};
EdgeSteps StepsAcrossEdges(const std::vector<fs::path>& leaves) {
  using Key = std::tuple<long long, long long, long long>;
  const auto key = [](const Eigen::Vector3d& p) {
    return Key(std::llround(p.x() * 1e4), std::llround(p.y() * 1e4), std::llround(p.z() * 1e4));
  };
  std::vector<testing::GlbTriangles> tiles;
  for (const fs::path& leaf : leaves) tiles.push_back(testing::ReadGlbTriangles(leaf));
  struct Side {
    std::size_t tile, triangle;
    int corner;  // the edge runs from this corner to the next
  };
  std::map<std::pair<Key, Key>, std::vector<Side>> sides_of_edge;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    for (std::size_t t = 0; t < tiles[i].corners_in_model.size(); ++t) {
      if (tiles[i].triangle_image[t] < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const Key a = key(tiles[i].corners_in_model[t][k]), b = key(tiles[i].corners_in_model[t][(k + 1) % 3]);
        sides_of_edge[std::minmax(a, b)].push_back({i, t, k});
      }
    }
  }
  const auto colour = [&](const Side& side, const Key& start, double along) {
    const testing::GlbTriangles& tile = tiles[side.tile];
    const int i = side.corner, j = (side.corner + 1) % 3, o = (side.corner + 2) % 3;
    if (key(tile.corners_in_model[side.triangle][i]) != start) along = 1.0 - along;
    std::array<double, 3> b{};
    b[i] = 0.9 * (1.0 - along);
    b[j] = 0.9 * along;
    b[o] = 0.1;
    return tile.AlbedoAt(side.triangle, b[1], b[2]);
  };
  EdgeSteps steps;
  for (const auto& [edge, sides] : sides_of_edge) {
    if (sides.size() != 2) continue;
    double step = 0.0;
    for (double along : {0.25, 0.5, 0.75}) {
      step += 100.0 * (colour(sides[0], edge.first, along) - colour(sides[1], edge.first, along)).cwiseAbs().mean() / 3.0;
    }
    if (sides[0].tile != sides[1].tile) {
      steps.tile_borders += step;
      ++steps.border_edges;
    } else {
      steps.inside_tiles += step;
      ++steps.inside_edges;
    }
  }
  steps.tile_borders /= double(std::max<std::size_t>(steps.border_edges, 1));
  steps.inside_tiles /= double(std::max<std::size_t>(steps.inside_edges, 1));
  return steps;
}

TEST(Tiles, ATilesetOfTheSurveyFollowsTheRulesAndKeepsTheColoursOfTheSingleBake) {
  testing::TempDir dir;
  const TilesSummary summary = TilesWorkspace(OptionsFor(dir.path() / "tiles", 2));
  EXPECT_GE(summary.depth, 2) << "2400 faces at 300 a tile make at least two levels below the root";
  const nlohmann::json tileset = nlohmann::json::parse(std::ifstream(dir.path() / "tiles" / "tileset.json"));
  EXPECT_EQ(tileset["asset"]["version"], "1.1");
  EXPECT_EQ(tileset["root"]["refine"], "REPLACE");
  ASSERT_TRUE(tileset["root"].contains("transform"));
  const double tileset_error = tileset["geometricError"];
  TileCheck check;
  CheckTile(tileset["root"], dir.path() / "tiles", tileset_error + 1e-12, check);
  EXPECT_EQ(check.tiles, summary.num_tiles);
  EXPECT_EQ(check.leaves, summary.num_leaves);
  const Mesh mesh = ReadMesh(SimulatedSurvey() / "W" / "scene" / "mesh.ply");
  EXPECT_EQ(check.leaf_triangles, mesh.faces.size()) << "the leaves hold every face once";

  // The root transform (column-major) takes the model's origin, the ENU origin, to its place on the globe,
  // with the model's up along the ellipsoid's normal there.
  Eigen::Matrix4d ecef_from_tiles;
  for (int i = 0; i < 16; ++i) ecef_from_tiles(i % 4, i / 4) = tileset["root"]["transform"][i];
  EXPECT_LT((ecef_from_tiles.topRightCorner<3, 1>() - EcefFromGeodetic(kEnuOrigin)).norm(), 1e-3);
  const double latitude = kEnuOrigin.x() * M_PI / 180.0, longitude = kEnuOrigin.y() * M_PI / 180.0;
  const Eigen::Vector3d normal(std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
                               std::sin(latitude));
  EXPECT_LT((ecef_from_tiles.block<3, 1>(0, 2) - normal).norm(), 1e-6);

  // The leaves' colours against the truth, as close as the single GLB's (same views, same fusion).
  TextureOptions texture;
  texture.workspace = SimulatedSurvey() / "W";
  texture.mesh = texture.workspace / "scene" / "mesh.ply";
  texture.views = OptionsFor({}, 2).views;
  texture.output = dir.path() / "model.glb";
  TextureWorkspace(texture);
  const double tiled = AlbedoError(check.leaf_contents, mesh);
  const double single = AlbedoError({dir.path() / "model.glb"}, mesh);
  std::cout << "albedo error at face centroids: tiles " << tiled << " pp, single GLB " << single << " pp\n";
  EXPECT_LT(tiled, 3.0);
  EXPECT_NEAR(tiled, single, 0.1);
  // The coarser levels, made from their children's textures, show the same colours with less detail (their
  // texels are 2, 4, 8, ... times the leaves'; the albedo changes from face to face, so the root, at 8 times,
  // is at 11 pp and the parents just above the leaves at 1 to 2.5). Parents baked from the images with
  // their own views, as before, were at 6.1 pp on average, against 3.5 now.
  const double parents = SurfaceAlbedoError(check.parent_contents, mesh);
  std::cout << "albedo error at the centroids of the " << check.parent_contents.size() << " parents' triangles: "
            << parents << " pp\n";
  EXPECT_LT(parents, 5.0);

  // A tile border is not a seam: the colour steps across it are those inside the tiles.
  const EdgeSteps steps = StepsAcrossEdges(check.leaf_contents);
  std::cout << "colour step across " << steps.border_edges << " tile-border edges " << steps.tile_borders
            << " pp, across " << steps.inside_edges << " edges inside tiles " << steps.inside_tiles << " pp\n";
  EXPECT_GT(steps.border_edges, 50u);
  EXPECT_LT(steps.tile_borders, steps.inside_tiles + 0.2);
}

TEST(Tiles, TheFilesDoNotDependOnTheThreadCount) {
  testing::TempDir dir;
  TilesWorkspace(OptionsFor(dir.path() / "one", 1));
  TilesWorkspace(OptionsFor(dir.path() / "two", 2));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path() / "one")) {
    const fs::path other = dir.path() / "two" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    std::ostringstream a, b;
    a << std::ifstream(entry.path(), std::ios::binary).rdbuf();
    b << std::ifstream(other, std::ios::binary).rdbuf();
    EXPECT_TRUE(a.str() == b.str()) << entry.path().filename() << " differs";
    ++files;
  }
  EXPECT_GT(files, 2u);
}

TEST(Tiles, WithoutAGeoreferenceTheTilesetHasNoTransform) {
  testing::TempDir dir;
  TilesOptions options = OptionsFor(dir.path() / "tiles", 2);
  options.georeference.enu_origin.clear();
  options.tree.max_faces = 100000;
  const TilesSummary summary = TilesWorkspace(options);
  EXPECT_EQ(summary.num_tiles, 1u);
  const nlohmann::json tileset = nlohmann::json::parse(std::ifstream(dir.path() / "tiles" / "tileset.json"));
  EXPECT_FALSE(tileset["root"].contains("transform"));
  EXPECT_EQ(tileset["root"]["geometricError"], 0.0);
  EXPECT_GT(tileset["geometricError"], 4.0) << "the root's diagonal: drawn once it is larger than a few pixels";
}

}  // namespace
}  // namespace lutex
