#include "colmap_integration/stages/tiles_workspace.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <iomanip>
#include <stdexcept>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/geo/earth_frame.h"
#include "lib/geo/map_frame.h"
#include "lib/util/atomic_output.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"
#include "texturing/gltf_export.h"
#include "texturing/gltf_frame.h"
#include "texturing/texture_transfer.h"
#include "texturing/tile_mesh.h"
#include "texturing/tile_views.h"
#include "texturing/tileset_json.h"
#include "texturing/waiting_tile.h"

namespace lutex {

namespace fs = std::filesystem;

void TilesOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (mesh.empty()) throw OptionError("{mesh} is required");
  CheckUpAxis(up_axis);
  georeference.Check();
  baking.Check();
  tree.Check();
}

namespace {

// Leaves' worth of faces in a leaf's piece, for the memory estimate (see TilesWorkspace).
constexpr std::size_t kPieceLeaves = 8;

InputsAndOutputs PathsOf(const TilesOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths = ViewStageInputs(workspace, options.mesh, options.views, "the images to texture from");
  paths.AddOutput(options.output.empty() ? workspace.TilesDir() : options.output);
  return paths;
}

double TexturedArea(const TexturedMesh& textured) {
  double area = 0.0;
  for (std::size_t f = 0; f < textured.mesh.faces.size(); ++f) {
    if (textured.face_page[f] < 0) continue;
    const Mesh::Face& face = textured.mesh.faces[f];
    const std::vector<Eigen::Vector3d>& v = textured.mesh.vertices;
    area += 0.5 * (v[face[1]] - v[face[0]]).cross(v[face[2]] - v[face[0]]).norm();
  }
  return area;
}

// What a finished tile hands to its parent: its geometry, its texture at half the resolution and the
// view of each face, on disk while it waits (texturing/waiting_tile.h), and in memory only what the
// tileset needs.
struct BakedTile {
  Eigen::AlignedBox3d box;         // of its content and its children's, in the tiles frame
  double geometric_error = 0.0;
  double texel_size = 0.0;         // scene units per texel of its texture
  fs::path waiting;                // the WaitingTile's file (none for the root)
};

// Bakes the tree bottom-up, writing each tile's GLB into `folder` and its entry into `tileset`.
class TileBaker {
 public:
  TileBaker(const TileTree& tree, const std::vector<TextureView>& views, const ViewImageSource& source,
            TiledViewChoice& choice, const TilesOptions& options, const TexturedMesh& frame,
            const Eigen::Matrix3d& tiles_from_model, fs::path folder, Tileset& tileset, TilesSummary& summary)
      : tree_(tree), views_(views), source_(source), choice_(choice), options_(options), frame_(frame),
        tiles_from_model_(tiles_from_model), folder_(std::move(folder)), waiting_folder_(folder_ / "waiting"),
        tileset_(tileset), summary_(summary) {
    fs::create_directories(waiting_folder_);
    tileset_.tiles.resize(tree_.nodes.size());
    for (std::size_t n = 0; n < tree_.nodes.size(); ++n) {
      if (tree_.nodes[n].children.empty()) leaf_of_node_[n] = leaf_of_node_.size();
    }
  }

  BakedTile Bake(std::size_t node_index) {
    const TileNode& node = tree_.nodes[node_index];
    BakedTile baked;
    WaitingTile made;  // what the parent will be made from
    TexturedMesh textured;
    if (node.children.empty()) {
      TextureBakingSummary baking;
      const TilePiece piece = choice_.Choose(leaf_of_node_.at(node_index), source_);
      std::vector<std::uint32_t> vertex_in_piece;
      textured = BakeFaces(piece.piece.mesh, views_, *piece.raycaster, source_, piece.chosen,
                           piece.tile_faces, options_.baking, vertex_in_piece, baking);
      for (std::uint32_t v : vertex_in_piece) made.geometry.source_vertex.push_back(piece.piece.source_vertex[v]);
      made.geometry.mesh = textured.mesh;
      for (std::uint32_t f : piece.tile_faces) made.view_of_face.push_back(piece.chosen.selection.view_of_face[f]);
      baked.texel_size = baking.num_texels > 0 ? std::sqrt(TexturedArea(textured) / double(baking.num_texels))
                                               : options_.baking.charts.texel_size;
      leaf_texel_sizes_.push_back(baked.texel_size);
      summary_.num_faces += textured.mesh.faces.size();
      summary_.num_textured_faces += textured.NumTexturedFaces();
    } else {
      std::vector<BakedTile> children;
      for (std::size_t child : node.children) children.push_back(Bake(child));
      std::vector<WaitingTile> waited;  // read back now that the last child is done
      double children_error = 0.0, children_texel = 0.0;
      for (const BakedTile& child : children) {
        waited.push_back(ReadWaitingTile(child.waiting));
        fs::remove(child.waiting);
        baked.box.extend(child.box);
        children_error = std::max(children_error, child.geometric_error);
        children_texel = std::max(children_texel, child.texel_size);
      }
      std::vector<const TileMesh*> parts;
      std::vector<TransferSource> textures;
      for (const WaitingTile& child : waited) {
        parts.push_back(&child.geometry);
        textures.push_back({&child.halved_texture, &child.view_of_face});
      }
      SimplifiedTileMesh simplified = SimplifyTileMesh(MergeTileMeshes(parts), options_.tree.max_faces);
      made.geometry = std::move(simplified.tile);
      baked.texel_size = 2.0 * children_texel;
      TextureBakingOptions baking = options_.baking;
      baking.charts.texel_size = baked.texel_size;
      // The children's surface lies within the simplification's error of the parent's; a few texels more
      // cover the rounding of both.
      TransferredTexture transferred = TransferTexture(textures, made.geometry.mesh, views_,
                                                       simplified.error + 4.0 * baked.texel_size, baking);
      waited.clear();
      textured = std::move(transferred.textured);
      made.view_of_face = std::move(transferred.view_of_face);
      baked.geometric_error = std::max(simplified.error + children_error, baked.texel_size);
    }
    for (const Eigen::Vector3d& vertex : made.geometry.mesh.vertices) baked.box.extend(tiles_from_model_ * vertex);
    textured.up = frame_.up;
    textured.georeference = frame_.georeference;
    const std::string uri = node.name + ".glb";
    if (node_index != 0) {
      made.halved_texture = HalveTexture(textured);
      baked.waiting = waiting_folder_ / (node.name + ".tile");
      WriteWaitingTile(made, baked.waiting);
    }
    made = WaitingTile();
    const std::size_t num_faces = textured.mesh.faces.size();
    WriteInBackground(std::move(textured), folder_ / uri);
    summary_.max_tile_faces = std::max(summary_.max_tile_faces, num_faces);
    TilesetTile& tile = tileset_.tiles[node_index];
    tile.box = baked.box;
    tile.geometric_error = baked.geometric_error;
    tile.content_uri = uri;
    tile.children = node.children;
    LogInfo() << "tiles: " << ++done_ << "/" << tree_.nodes.size() << " tiles baked (" << node.name << ", "
              << num_faces << " faces)";
    if (node_index == 0) fs::remove_all(waiting_folder_);  // every tile has been read back
    return baked;
  }

  const std::vector<double>& leaf_texel_sizes() const { return leaf_texel_sizes_; }

  // Waits for the last tile's file; rethrows what writing it threw.
  void FinishWriting() {
    if (writing_.valid()) writing_.get();
  }

 private:
  // A tile's GLB (PNG encoding, mostly one core's work) is written while the next tile is baked, on one
  // thread more than --num-threads; at most one is pending, so memory holds one finished tile more until
  // its file is written.
  void WriteInBackground(TexturedMesh textured, fs::path path) {
    FinishWriting();
    writing_ = std::async(std::launch::async, [this, textured = std::move(textured), path = std::move(path)]() mutable {
      const TexturedMesh written = std::move(textured);  // freed when the file is written
      WriteGltf(written, path, options_.gltf);
    });
  }

  const TileTree& tree_;
  const std::vector<TextureView>& views_;
  const ViewImageSource& source_;
  TiledViewChoice& choice_;
  std::map<std::size_t, std::size_t> leaf_of_node_;  // the index of each leaf among the choice's tiles
  const TilesOptions& options_;
  const TexturedMesh& frame_;  // its up and georeference
  const Eigen::Matrix3d tiles_from_model_;
  const fs::path folder_;
  const fs::path waiting_folder_;  // the waiting tiles' files, in folder_ and removed when the root is done
  Tileset& tileset_;
  TilesSummary& summary_;
  std::size_t done_ = 0;
  std::vector<double> leaf_texel_sizes_;
  std::future<void> writing_;  // the previous tile's GLB
};

int Depth(const TileTree& tree) {
  int depth = 0;
  for (const TileNode& node : tree.nodes) depth = std::max(depth, node.depth);
  return depth;
}

}  // namespace

TilesSummary TilesWorkspace(const TilesOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  LoadedDive dive(options.workspace, options.mesh);
  return TilesWorkspace(options, dive);
}

TilesSummary TilesWorkspace(const TilesOptions& options, LoadedDive& dive) {
  options.Check();
  const InputsAndOutputs paths = PathsOf(options, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  // A leaf's views are chosen on its piece, the leaf and the surface around it within reach of the views
  // that see it (tile_views.h), taken as kPieceLeaves leaves' worth: the pieces held up to 1.8 leaves'
  // worth of faces on the tiles benchmark's survey and 5.8 on the 12 MP one (README, 'Speed and memory').
  const std::size_t piece_faces = std::min(dive.mesh().faces.size(), kPieceLeaves * options.tree.max_faces);
  MemoryEstimate baking_memory = TextureBakingMemory(options.baking, piece_faces);
  baking_memory.Add("the decoded-picture cache", 1.0,
                    PictureCacheBytes(dive.model(), options.views.image_encoding, options.picture_cache_bytes));
  CheckStageMemory("tiles", dive, options.baking.num_threads, kImageStageBytesPerPixel, options.memory_limit_bytes,
                   baking_memory, piece_faces);
  const auto start = std::chrono::steady_clock::now();
  const Workspace& workspace = dive.workspace();
  const fs::path output = options.output.empty() ? workspace.TilesDir() : options.output;
  WorkspaceViewsOptions views_options = options.views;
  views_options.picture_cache_bytes = options.picture_cache_bytes;
  const WorkspaceViews found = FindWorkspaceViews(workspace, dive.model(), views_options, "tiles");
  const ViewImageSource source = found.Source();
  TilesSummary summary;
  summary.images = found.images;
  summary.georeference = ResolveGeoreference(options.georeference, workspace);
  const Georeference& georeference = summary.georeference.georeference;
  std::unique_ptr<MapFrame> map_frame;
  if (georeference.IsSet()) map_frame = std::make_unique<MapFrame>(georeference);  // checks the CRS
  summary.up = ResolveModelUp(options.up_axis, summary.georeference, dive.model());
  const Eigen::Matrix3d tiles_from_model = TilesFromModel(summary.up.up);
  if (found.views.empty()) throw std::invalid_argument("tiles: no views to texture from");

  TileTree tree = PartitionIntoTiles(dive.mesh(), tiles_from_model, options.tree);
  summary.num_tiles = tree.nodes.size();
  summary.num_leaves = tree.NumLeaves();
  summary.depth = Depth(tree);
  LogInfo() << "tiles: " << tree.nodes.size() << " tiles, " << summary.num_leaves << " leaves of at most "
            << options.tree.max_faces << " faces, " << summary.depth << " levels below the root";

  std::vector<const std::vector<std::uint32_t>*> leaves;
  for (const TileNode& node : tree.nodes) {
    if (node.children.empty()) leaves.push_back(&node.faces);
  }
  AtomicOutputFile folder(output);
  fs::create_directories(folder.temporary_path());
  // From here on the mesh is read from disk a piece at a time: what the dive held is freed.
  // The choice's scratch file is in the folder: it goes before the folder is committed.
  auto choice = std::make_unique<TiledViewChoice>(dive.mesh(), found.views, leaves, options.baking,
                                                  folder.temporary_path() / "mesh");
  dive.ReleaseMesh();
  for (TileNode& node : tree.nodes) std::vector<std::uint32_t>().swap(node.faces);
  TexturedMesh frame;
  frame.up = summary.up.up;
  frame.georeference = georeference;
  Tileset tileset;
  TileBaker baker(tree, found.views, source, *choice, options, frame, tiles_from_model, folder.temporary_path(),
                  tileset, summary);
  baker.Bake(0);
  baker.FinishWriting();
  summary.seconds_views = choice->seconds();
  summary.levelling = choice->levelling();
  summary.max_piece_faces = choice->max_piece_faces();
  choice.reset();
  std::vector<double> texels = baker.leaf_texel_sizes();
  std::nth_element(texels.begin(), texels.begin() + texels.size() / 2, texels.end());
  summary.leaf_texel_size = texels[texels.size() / 2];

  summary.root_geometric_error = tileset.tiles[0].geometric_error;
  tileset.geometric_error = std::max(2.0 * summary.root_geometric_error, tileset.tiles[0].box.diagonal().norm());
  if (map_frame) {
    const Eigen::Matrix3d model_from_tiles = tiles_from_model.transpose();
    Eigen::Matrix4d model_from_tiles_4 = Eigen::Matrix4d::Identity();
    model_from_tiles_4.topLeftCorner<3, 3>() = model_from_tiles;
    tileset.ecef_from_tiles =
        EcefFromModelNear(*map_frame, model_from_tiles * tileset.tiles[0].box.center()) * model_from_tiles_4;
  } else {
    LogWarning() << "tiles: the model is not georeferenced (no --crs or --enu-origin, no " << workspace.GeoreferencePath().string()
                 << "): the tileset has no transform and will not sit on the globe";
  }
  nlohmann::json extras;
  extras["up_in_model"] = {summary.up.up.x(), summary.up.up.y(), summary.up.up.z()};
  extras["georeference"] = {{"frame", FrameName(georeference.frame)}};
  if (georeference.IsSet()) {
    if (!georeference.crs.empty()) extras["georeference"]["crs"] = georeference.crs;
    extras["georeference"]["origin"] = {georeference.origin.x(), georeference.origin.y(), georeference.origin.z()};
  }
  tileset.lutex_extras_json = extras.dump();
  WriteTilesetJson(tileset, folder.temporary_path() / "tileset.json");
  folder.Commit();
  summary.tileset = output / "tileset.json";
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintTilesSummary(std::ostream& out, const TilesSummary& summary) {
  out << std::fixed << std::setprecision(1) << "tiles: " << summary.num_tiles << " tiles (" << summary.num_leaves
      << " leaves, " << summary.depth << " levels below the root) in " << summary.seconds << " s\n"
      << "  faces: " << summary.num_textured_faces << " of " << summary.num_faces << " textured in the leaves; at most "
      << summary.max_tile_faces << " in one tile\n"
      << std::setprecision(4) << "  texel size of the leaves: " << summary.leaf_texel_size
      << " (median); root geometric error " << summary.root_geometric_error << "\n"
      << "  seam levelling: " << DescribeSeamLevelling(summary.levelling) << "\n"
      << std::setprecision(1) << "  time: views and seam levelling, tile by tile (at most " << summary.max_piece_faces
      << " faces with the surface around a tile) " << summary.seconds_views << " s\n"
      << "  images: " << summary.images.string() << "\n"
      << "  georeference: " << summary.georeference.georeference.Describe() << " from " << summary.georeference.source
      << (summary.georeference.georeference.IsSet() ? " (the root transform places the tiles on the globe)\n"
                                                     : " (no root transform: the tiles are in the model's frame)\n")
      << "  up: " << DescribeModelUp(summary.up, summary.georeference) << "\n"
      << "  wrote " << summary.tileset.string() << "\n";
}

}  // namespace lutex
