#pragma once

// `lutex tiles`: the textured mesh as OGC 3D Tiles 1.1 for web map viewers (CesiumJS and those built on
// it), baked tile by tile.
//
//   1. the model's up and georeference (model_up.h, workspace_georeference.h)
//   2. a quadtree of tiles over the mesh's horizontal footprint, at most `tree.max_faces` faces a leaf
//      (texturing/tile_tree.h)
//   3. each leaf's views chosen on its own piece of the mesh, the leaf and the surface around it that may
//      hide it, with the labels and seam corrections of the leaves done before fixed at its border
//      (texturing/tile_views.h), so that labels and the colours fused from them agree across tile borders
//   4. the leaf's faces baked with those labels and written as DIR/tiles/NAME.glb, then freed with its piece
//   5. each parent, once its children are done: their meshes merged and simplified to the face budget
//      with the tile's border locked (texturing/tile_mesh.h), textured at twice their coarsest texel size
//      from their textures (texturing/texture_transfer.h; no image is read again, and a level shows the
//      colours of the level below), written, and the children freed
//   6. DIR/tileset.json (texturing/tileset_json.h): boxes, geometric errors (0 for leaves; a parent's is
//      its simplification error plus its children's, and at least its texel size), refine REPLACE, and
//      the root transform to ECEF from the georeference (lib/geo/earth_frame.h); without one, a local
//      frame and a warning that the tiles will not sit on the globe.
//
// The folder is written under a temporary name beside DIR and renamed into place when complete.
// Memory: the mesh, a label per face and the corrections at the leaves' borders; one leaf's piece
// (its ray-casting scene, adjacency and candidates) and one tile's bake at a time, with
// at most three finished children per level of the tree (their meshes and their textures at half the
// resolution: a quarter of their texels), plus the decoded-picture cache.

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/model_up.h"
#include "colmap_integration/stages/workspace_georeference.h"
#include "colmap_integration/stages/workspace_views.h"
#include "texturing/gltf_export.h"
#include "texturing/texture_baker.h"
#include "texturing/tile_tree.h"

namespace lutex {

struct TilesOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  WorkspaceViewsOptions views;
  std::filesystem::path output;  // the folder; empty: W/lutex/tiles
  TextureBakingOptions baking;
  GltfOptions gltf;  // of every tile's GLB
  TileTreeOptions tree;
  std::string up_axis = "auto";  // as for `lutex texture`
  GeoreferenceOptions georeference;
  std::size_t memory_limit_bytes = 0;  // 0: the machine's available memory (stage_memory.h)
  // Decoded pictures and confidence maps kept for the next tiles (views.picture_cache_bytes): a view is
  // read once per tile that sees it, and neighbouring tiles see mostly the same views (kDefaultPictureCacheBytes). 0: none.
  std::size_t picture_cache_bytes = kDefaultPictureCacheBytes;
  void Check() const;
};

struct TilesSummary {
  std::filesystem::path tileset;  // DIR/tileset.json
  std::filesystem::path images;
  std::size_t num_tiles = 0;
  std::size_t num_leaves = 0;
  int depth = 0;  // levels below the root
  std::size_t num_faces = 0;
  std::size_t num_textured_faces = 0;
  std::size_t max_tile_faces = 0;   // most faces written in one tile
  double root_geometric_error = 0.0;
  double leaf_texel_size = 0.0;     // median over the leaves, scene units
  ModelUp up;
  WorkspaceGeoreference georeference;
  double seconds_views = 0.0;       // visibility, view selection and seam levelling, tile by tile
  std::size_t max_piece_faces = 0;  // the most faces a tile's views were chosen on (tile_views.h)
  SeamLevellingSummary levelling;
  double seconds = 0.0;
};

TilesSummary TilesWorkspace(const TilesOptions& options);
// Releases the dive's mesh (LoadedDive::ReleaseMesh) once it is on disk tile by tile.
TilesSummary TilesWorkspace(const TilesOptions& options, LoadedDive& dive);

void PrintTilesSummary(std::ostream& out, const TilesSummary& summary);

}  // namespace lutex
