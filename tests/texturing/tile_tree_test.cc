// The quadtree of a tiled bake (texturing/tile_tree.h), checked against the faces' own centroids: every
// face in exactly the one leaf under its centroid, leaves within the face budget, quadrants where their
// names say, and the same tree whatever order the faces come in.

#include "texturing/tile_tree.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"

namespace lutex {
namespace {

void Append(const Mesh& more, Mesh* mesh) {
  const auto offset = static_cast<std::uint32_t>(mesh->vertices.size());
  mesh->vertices.insert(mesh->vertices.end(), more.vertices.begin(), more.vertices.end());
  for (Mesh::Face face : more.faces) {
    for (std::uint32_t& v : face) v += offset;
    mesh->faces.push_back(face);
  }
}

// A rolling floor of 2 × 61 × 37 faces, twice as dense in its western half so that the tree is uneven.
Mesh Floor() {
  Mesh west = MakeHeightFieldMesh([](double x, double y) { return 0.3 * std::sin(x) * std::cos(y); }, 0.0, 3.0, 0.0,
                                  3.7, 40, 37);
  const Mesh east = MakeHeightFieldMesh([](double x, double y) { return 0.3 * std::sin(x) * std::cos(y); }, 3.0, 6.1,
                                        0.0, 3.7, 21, 37);
  Append(east, &west);
  return west;
}

// The tiles frame turned 30 degrees about the vertical from the model's.
Eigen::Matrix3d TilesFromModel() { return Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

Eigen::Vector2d CentroidInTiles(const Mesh& mesh, std::uint32_t f) {
  const Mesh::Face& face = mesh.faces[f];
  return (TilesFromModel() * ((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0))
      .head<2>();
}

// Whether a point is in a footprint (closed, to a nanometre: a centroid on a split line goes to one side).
bool Holds(const TileNode& node, const Eigen::Vector2d& point) {
  return (point.array() >= node.footprint.min().array() - 1e-9).all() &&
         (point.array() <= node.footprint.max().array() + 1e-9).all();
}

TEST(TileTree, EachFaceIsInTheOneLeafUnderItsCentroid) {
  const Mesh mesh = Floor();
  TileTreeOptions options;
  options.max_faces = 400;
  const TileTree tree = PartitionIntoTiles(mesh, TilesFromModel(), options);
  ASSERT_FALSE(tree.nodes.empty());
  const TileNode& root = tree.nodes[0];
  EXPECT_EQ(root.name, "0");
  EXPECT_NEAR(root.footprint.sizes().x(), root.footprint.sizes().y(), 1e-12) << "tiles are square";

  std::vector<int> leaf_of(mesh.faces.size(), -1);
  std::size_t leaves = 0;
  int deepest = 0;
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const TileNode& node = tree.nodes[n];
    deepest = std::max(deepest, node.depth);
    if (!node.children.empty()) {
      EXPECT_TRUE(node.faces.empty()) << node.name;
      for (std::size_t child : node.children) {
        ASSERT_GT(child, n) << "a parent comes before its children";
        const TileNode& kid = tree.nodes[child];
        EXPECT_EQ(kid.depth, node.depth + 1);
        ASSERT_EQ(kid.name.substr(0, node.name.size() + 1), node.name + "_");
        const int quadrant = std::stoi(kid.name.substr(node.name.size() + 1));
        const Eigen::Vector2d half = 0.5 * node.footprint.sizes();
        const Eigen::Vector2d low =
            node.footprint.min() + Eigen::Vector2d((quadrant & 1) ? half.x() : 0.0, (quadrant & 2) ? half.y() : 0.0);
        EXPECT_TRUE(kid.footprint.min().isApprox(low, 1e-12)) << kid.name;
        EXPECT_TRUE(kid.footprint.sizes().isApprox(half, 1e-12)) << kid.name;
      }
      continue;
    }
    ++leaves;
    EXPECT_FALSE(node.faces.empty()) << "empty quadrants are not kept: " << node.name;
    EXPECT_LE(node.faces.size(), options.max_faces) << node.name;
    EXPECT_TRUE(std::is_sorted(node.faces.begin(), node.faces.end())) << node.name;
    for (std::uint32_t f : node.faces) {
      ASSERT_LT(f, mesh.faces.size());
      EXPECT_EQ(leaf_of[f], -1) << "face " << f << " in two leaves";
      leaf_of[f] = static_cast<int>(n);
      EXPECT_TRUE(Holds(node, CentroidInTiles(mesh, f))) << "face " << f << " outside " << node.name;
    }
  }
  EXPECT_EQ(std::count(leaf_of.begin(), leaf_of.end(), -1), 0) << "every face is in a leaf";
  EXPECT_EQ(tree.NumLeaves(), leaves);
  EXPECT_GE(deepest, 3) << "the dense half is split further";
}

TEST(TileTree, TheSplitStopsAtTheMostDepth) {
  const Mesh mesh = Floor();
  TileTreeOptions options;
  options.max_faces = 10;
  options.max_depth = 1;
  const TileTree tree = PartitionIntoTiles(mesh, TilesFromModel(), options);
  std::size_t faces = 0;
  for (const TileNode& node : tree.nodes) {
    EXPECT_LE(node.depth, 1);
    faces += node.faces.size();
  }
  EXPECT_EQ(faces, mesh.faces.size());
  EXPECT_EQ(tree.NumLeaves(), tree.nodes.size() - 1);
}

TEST(TileTree, FacesInAnotherOrderMakeTheSameTree) {
  const Mesh mesh = Floor();
  Mesh shuffled = mesh;
  std::vector<std::uint32_t> old_of_new(mesh.faces.size());
  std::iota(old_of_new.begin(), old_of_new.end(), 0u);
  std::shuffle(old_of_new.begin(), old_of_new.end(), std::mt19937(5));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) shuffled.faces[f] = mesh.faces[old_of_new[f]];
  TileTreeOptions options;
  options.max_faces = 300;
  const TileTree tree = PartitionIntoTiles(mesh, TilesFromModel(), options);
  const TileTree other = PartitionIntoTiles(shuffled, TilesFromModel(), options);
  ASSERT_EQ(tree.nodes.size(), other.nodes.size());
  std::map<std::string, const TileNode*> by_name;
  for (const TileNode& node : other.nodes) by_name[node.name] = &node;
  for (const TileNode& node : tree.nodes) {
    ASSERT_EQ(by_name.count(node.name), 1u) << node.name;
    const TileNode& twin = *by_name[node.name];
    EXPECT_TRUE(twin.footprint.isApprox(node.footprint)) << node.name;
    std::vector<std::uint32_t> faces;
    for (std::uint32_t f : twin.faces) faces.push_back(old_of_new[f]);
    std::sort(faces.begin(), faces.end());
    EXPECT_EQ(faces, node.faces) << node.name;
  }
}

// A patch of 4,440 faces in a square centimetre of a floor a kilometre wide: the patch's tiles lie 17 to
// 20 levels down, deeper than one pass over the faces looks ahead, so the tree is made over several passes.
TEST(TileTree, ADensePatchOnAWideFloorIsSplitAsDeepAsItNeeds) {
  Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 1000.0, 0.0, 1000.0, 4, 4);
  const Mesh patch = MakeHeightFieldMesh([](double x, double y) { return 0.001 * std::sin(1000.0 * (x + y)); }, 500.0,
                                         500.01, 300.0, 300.01, 60, 37);
  Append(patch, &mesh);
  TileTreeOptions options;
  options.max_faces = 100;
  options.max_depth = 24;
  const TileTree tree = PartitionIntoTiles(mesh, TilesFromModel(), options);

  // Each tile's faces, summed up from its leaves (children come after their parent).
  std::vector<std::size_t> faces_in(tree.nodes.size(), 0);
  for (std::size_t n = tree.nodes.size(); n-- > 0;) {
    faces_in[n] = tree.nodes[n].faces.size();
    for (std::size_t child : tree.nodes[n].children) faces_in[n] += faces_in[child];
  }
  EXPECT_EQ(faces_in[0], mesh.faces.size());
  int deepest = 0;
  std::vector<int> leaves_of_face(mesh.faces.size(), 0);
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const TileNode& node = tree.nodes[n];
    deepest = std::max(deepest, node.depth);
    if (!node.children.empty()) {
      EXPECT_GT(faces_in[n], options.max_faces) << "split although it fits: " << node.name;
      continue;
    }
    EXPECT_LE(node.faces.size(), options.max_faces) << node.name;
    for (std::uint32_t f : node.faces) {
      ++leaves_of_face[f];
      EXPECT_TRUE(Holds(node, CentroidInTiles(mesh, f))) << "face " << f << " outside " << node.name;
    }
  }
  EXPECT_EQ(std::count(leaves_of_face.begin(), leaves_of_face.end(), 1),
            static_cast<std::ptrdiff_t>(mesh.faces.size()))
      << "every face in one leaf";
  EXPECT_GE(deepest, 17);
}

TEST(TileTree, RefusesAMeshWithoutFacesAndBadOptions) {
  EXPECT_THROW(PartitionIntoTiles(Mesh{}, Eigen::Matrix3d::Identity(), TileTreeOptions{}), std::invalid_argument);
  TileTreeOptions options;
  options.max_faces = 0;
  EXPECT_THROW(PartitionIntoTiles(Floor(), Eigen::Matrix3d::Identity(), options), std::invalid_argument);
  options.max_faces = 10;
  options.max_depth = 25;
  EXPECT_THROW(PartitionIntoTiles(Floor(), Eigen::Matrix3d::Identity(), options), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
