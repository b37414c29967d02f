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
// Visibility, view selection and seam levelling are solved once for the whole mesh (texture_baker.h
// ChooseViews, as for the texture: a cell's colour gets its face's seam correction); then each tile is
// laid out, fused (reading only the views that see its faces) and handed to the caller, then freed:
// memory is bounded by the tile size and the threads, not by the mosaic's size. Results do not depend on
// the thread count.

#include <cstddef>
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

// Casts 64 rows of the grid down: throws std::invalid_argument when none hits the mesh ("the mesh has no
// surface seen from above"), before any image is read or any file is created.
void CheckSurfaceFromAbove(const RaycastScene& scene, const MapFrame& frame, const OrthoGrid& grid, int num_threads);

struct OrthoMosaicOptions {
  TextureBakingOptions baking;  // visibility, selection and fusion are the texture's
  int tile_size = 1024;          // cells per side of a tile
  void Check() const;
};

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
  std::size_t num_views = 0;
  std::size_t tile_view_reads = 0;  // images read over all tiles (a view is read by each tile it reaches)
  double mean_samples_per_cell = 0.0;
  SeamLevellingSummary levelling;
  double seconds_selection = 0.0;  // visibility, view selection and seam levelling
  double seconds_tiles = 0.0;
};

// Hands every tile, row by row, to `write_tile` (from the calling thread). Throws what
// CheckSurfaceFromAbove, the image source and `write_tile` throw.
OrthoMosaicSummary MakeOrthoMosaic(const Mesh& mesh, const RaycastScene& scene, const std::vector<TextureView>& views,
                                   const ViewImageSource& source, const MapFrame& frame, const OrthoGrid& grid,
                                   const OrthoMosaicOptions& options,
                                   const std::function<void(const OrthoTile&)>& write_tile);

}  // namespace lutex
