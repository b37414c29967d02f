#pragma once

// `lutex mosaic`: the georeferenced orthomosaic and DEM of a COLMAP workspace, as Cloud-Optimized
// GeoTIFFs (texturing/ortho_mosaic.h for what a cell shows, lib/geo/cog_writer.h for the files).
//
// Inputs: the workspace's model and the mesh; the images to map (workspace_views.h: the restored images by
// default) and their confidence maps; the georeference (workspace_georeference.h: options or
// W/georef.json). All are checked before anything is written.
// Outputs: default W/lutex/mosaic/ortho.tif (8-bit sRGB + alpha, or 16-bit linear + alpha) and
// W/lutex/mosaic/dem.tif (float32 map heights, NaN nodata), same grid and CRS.

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/workspace_georeference.h"
#include "colmap_integration/stages/workspace_views.h"
#include "texturing/ortho_mosaic.h"

namespace lutex {

struct MosaicOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  WorkspaceViewsOptions views;  // the images to map and their confidence
  GeoreferenceOptions georeference;
  // Metres per pixel in the map CRS; 0: the images' own, the median over images of (depth at the image
  // centre / focal length in pixels).
  double gsd = 0.0;
  std::filesystem::path output;  // empty: W/lutex/mosaic/ortho.tif
  std::filesystem::path dem;     // empty: W/lutex/mosaic/dem.tif
  bool no_dem = false;
  ImageEncoding encoding = ImageEncoding::kSrgb8;  // srgb8 or linear16
  // GDAL's block cache while the GeoTIFFs are written and converted.
  std::size_t gdal_cache_bytes = std::size_t{256} << 20;
  OrthoMosaicOptions ortho;  // tile size, and the texture's visibility, selection and fusion
  // The stage refuses to start when its memory estimate (stage_memory.h) exceeds this; 0: the machine's
  // available memory. The estimate counts the fusion's budget (ortho.baking.fusion) and the faces'
  // tables as parts.
  std::size_t memory_limit_bytes = 0;
  // Decoded pictures and confidence maps kept for the next tiles (views.picture_cache_bytes): a view is
  // read once per tile of the grid that sees it, and the tiles, done row by row, see mostly the same
  // views as their neighbours (kDefaultPictureCacheBytes). 0: none.
  std::size_t picture_cache_bytes = kDefaultPictureCacheBytes;
  void Check() const;
};

struct MosaicSummary {
  std::filesystem::path ortho;
  std::filesystem::path dem;  // empty without one
  WorkspaceGeoreference georeference;
  std::string crs;       // the map CRS ("EPSG:32632"), empty for the model's own frame
  std::string crs_name;  // "WGS 84 / UTM zone 32N"
  OrthoGrid grid;
  bool gsd_from_images = false;
  std::filesystem::path images;
  std::filesystem::path confidence;
  OrthoMosaicSummary mosaic;
  // Images and confidence maps decoded over all tiles; the other reads came from the image cache.
  std::size_t files_decoded = 0;
  double seconds = 0.0;
};

// The images' own GSD (see MosaicOptions::gsd), the median of GsdsAtImageCentres's finite ones; throws
// std::invalid_argument when no image centre sees the mesh (all infinite).
double GsdOfViews(std::vector<double> gsds);

// Why a model with no georeference cannot be mapped in its own frame (its cameras do not look down its
// -z), or "" when it can.
std::string WhyNotAMapWithoutGeoreference(const SparseModel& model);

MosaicSummary MosaicWorkspace(const MosaicOptions& options);
// The same on a dive loaded before: `dive` holds the workspace and mesh of `options`.
// Releases the dive's mesh (LoadedDive::ReleaseMesh) once it is on disk block by block.
MosaicSummary MosaicWorkspace(const MosaicOptions& options, LoadedDive& dive);

// The lines the stage prints when done.
void PrintMosaicSummary(std::ostream& out, const MosaicSummary& summary);

}  // namespace lutex
