#pragma once

// A top-down map of a mesh's albedo (the orthomosaic) and of its heights (the DEM), on a north-up grid of
// a map frame (lib/geo/map_frame.h), made tile by tile.
//
// Each grid cell shows the topmost surface point of the mesh under its centre: the first hit of a ray cast
// straight down (along the map frame's vertical, converted into the model's frame) from above the mesh.
// Its colour is fused from every view that sees that point exactly as a texel of the texture atlas is
// (texel_fusion.h: depth-consistent bilinear sampling, confidence x angle x resolution weights, outlier
// rejection, the view the MRF chose for the face breaking ties): a tile of the mosaic is one more texel
// layout for the same fusion. Its height is the point's height in the map frame. Cells with no surface
// below them, or whose surface no view sees, are nodata (NaN).
//
// The tiles are grouped in square blocks about an image's footprint wide (OrthoTiling), and each face
// goes to the block its centroid lies over. Block by block (tile_views.h TiledViewChoice): the block's
// piece is its faces and every face that may hide them or lie over its cells, with its own ray-casting
// scene; the views of the block's faces and of the faces its cells may show are chosen and their seams
// levelled, with the labels and corrections of the blocks before held (so a face shows one label and one
// correction, whichever block's cells show it); then each of its tiles, row by row, is cast down on the
// piece, fused (reading only the views that see it), handed to the caller and freed, and the piece after
// them. Memory is bounded by the tile and block size and the threads, plus a block and a label per face
// and the corrections settled along block borders; not by the mosaic's size. Results do not depend on
// the thread count.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "lib/geo/cog_writer.h"
#include "lib/geo/map_frame.h"
#include "lib/geometry/mesh.h"
#include "lib/raycast/raycast_scene.h"
#include "texturing/texture_baker.h"
#include "texturing/texture_views.h"

namespace lutex {

// The grid of a mosaic: the mesh's footprint in the map frame, its corners snapped to multiples of the
// GSD (so mosaics of one survey at one GSD share their pixel grid), and the map heights that bound it.
struct OrthoGrid {
  GeoRasterGrid raster;  // width, height, west, north, gsd, CRS
  double bottom = 0.0;   // lowest and highest map height of the mesh
  double top = 0.0;
};

// Most cells a mosaic may have (an 80 000 x 80 000 grid); a finer GSD is refused with the size it would be.
constexpr double kMaxOrthoCells = 6.4e9;

// Throws std::invalid_argument when `gsd` is not positive or the grid would exceed kMaxOrthoCells
// ("--gsd 1e-05 would make a mosaic of 1000000 x 800000 pixels (8e+11); ..."), and what the frame throws.
OrthoGrid OrthoGridOfMesh(const Mesh& mesh, const MapFrame& frame, double gsd);

// Throws std::invalid_argument when no face of the mesh can be seen from above: every face is vertical
// in the map frame, or degenerate ("the mesh has no surface seen from above"). Before any image is read
// or any file is created.
void CheckSurfaceFromAbove(const Mesh& mesh, const MapFrame& frame);

struct OrthoMosaicOptions {
  TextureBakingOptions baking;  // visibility, selection and fusion are the texture's
  int tile_size = 1024;          // cells per side of a tile
  void Check() const;
};

// The mosaic's tiles (tile_size cells a side, the last of a row or column cut at the grid's edge), in
// square blocks of block_side tiles a side whose views are chosen together, and the faces of the mesh
// each block holds: those whose centroid lies over its cells.
struct OrthoTiling {
  int tile_size = 0;
  int tiles_x = 0;
  int tiles_y = 0;
  int block_side = 1;
  int blocks_x = 0;
  int blocks_y = 0;
  std::vector<std::vector<std::uint32_t>> faces;  // per block, row by row, ascending

  std::size_t num_tiles() const { return static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y); }
  std::size_t num_blocks() const { return faces.size(); }
  // The cells of a block, and of its tiles (row by row).
  cv::Rect BlockCells(std::size_t block, const GeoRasterGrid& raster) const;
  std::vector<cv::Rect> TilesOfBlock(std::size_t block, const GeoRasterGrid& raster) const;
  std::size_t MostFaces() const;  // of a block
};

// Each view's ground sampling distance at its image centre: the range along its optical axis to the mesh
// over its focal length in pixels (metres per pixel; +infinity where the axis misses the mesh). The ranges
// are found in one pass over the faces (lib/raycast/few_ray_hits.h).
std::vector<double> GsdsAtImageCentres(const Mesh& mesh, const std::vector<TextureView>& views);

// Tiles a side of a block: about as many as the median view's footprint on the mesh spans (its image
// width times the range at its centre over its focal length), at least 1 and at most 8192 cells. A tile's
// views are chosen on the surface within reach of the views that see it, about half a footprint around
// it: a block as wide as a footprint shares that work among its tiles, at about four blocks' worth of
// faces a piece (tile_views.h).
// `gsds`: GsdsAtImageCentres's, one per view.
int OrthoBlockSide(const std::vector<double>& gsds, const std::vector<TextureView>& views, const OrthoGrid& grid,
                   int tile_size);

// One pass over the mesh's faces.
OrthoTiling TileOrthoGrid(const Mesh& mesh, const MapFrame& frame, const OrthoGrid& grid, int tile_size,
                          int block_side);

// One finished tile: cells [col, col + colour.cols) x [row, row + colour.rows) of the grid.
struct OrthoTile {
  int col = 0;
  int row = 0;
  cv::Mat colour;  // linear RGB CV_32FC3, NaN where nodata
  cv::Mat height;  // map height CV_32FC1, NaN where no surface
};

struct OrthoMosaicSummary {
  std::size_t num_cells = 0;
  std::size_t surface_cells = 0;  // with a surface below them
  std::size_t seen_cells = 0;     // with a colour
  std::size_t num_tiles = 0;
  std::size_t num_blocks = 0;  // of tiles whose views are chosen together (OrthoTiling)
  std::size_t num_views = 0;
  std::size_t tile_view_reads = 0;  // images read over all tiles (a view is read by each tile it reaches)
  double mean_samples_per_cell = 0.0;
  SeamLevellingSummary levelling;
  double seconds_selection = 0.0;  // visibility, view selection and seam levelling
  double seconds_tiles = 0.0;      // the rest
  std::size_t max_piece_faces = 0;  // the most faces a block's piece held
};

// Hands every tile, block by block and in a block row by row, to `write_tile` (from the calling thread).
// `tiling`: TileOrthoGrid's for options.tile_size when the caller has made it (null: made here, with
// OrthoBlockSide's blocks). The mesh is kept on disk block by block beside `scratch` while the mosaic is
// made (tile_views.h), under a temporary name; then `mesh_on_disk`, when given, is called: neither `mesh`
// nor the tiling's face lists are used after it, and the caller may free them. Throws what
// CheckSurfaceFromAbove, the image source and `write_tile` throw.
OrthoMosaicSummary MakeOrthoMosaic(const Mesh& mesh, const std::vector<TextureView>& views,
                                   const ViewImageSource& source, const MapFrame& frame, const OrthoGrid& grid,
                                   const OrthoMosaicOptions& options,
                                   const std::function<void(const OrthoTile&)>& write_tile,
                                   const std::filesystem::path& scratch, const OrthoTiling* tiling = nullptr,
                                   const std::function<void()>& mesh_on_disk = {});

}  // namespace lutex
