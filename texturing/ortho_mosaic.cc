#include "texturing/ortho_mosaic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"
#include "texturing/face_adjacency.h"
#include "texturing/texel_fusion.h"
#include "texturing/texel_layout.h"

namespace lutex {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The first surface point below each cell of `cells` (row-major): rays from above the mesh's top to below
// its bottom, along the map vertical, in the model's frame. Misses and hits beyond the bottom have no face.
std::vector<RayHit> CastCellsDown(const RaycastScene& scene, const MapFrame& frame, const OrthoGrid& grid,
                                  const cv::Rect& cells, int num_threads) {
  const std::size_t n = static_cast<std::size_t>(cells.area());
  const double margin = 1.0 + 0.01 * (grid.top - grid.bottom);
  std::vector<Eigen::Vector3d> tops(n), bottoms(n);
  const GeoRasterGrid& raster = grid.raster;
  for (int r = 0; r < cells.height; ++r) {
    for (int c = 0; c < cells.width; ++c) {
      const double east = raster.west + (cells.x + c + 0.5) * raster.gsd;
      const double north = raster.north - (cells.y + r + 0.5) * raster.gsd;
      const std::size_t i = static_cast<std::size_t>(r) * cells.width + c;
      tops[i] = {east, north, grid.top + margin};
      bottoms[i] = {east, north, grid.bottom - margin};
    }
  }
  frame.ModelFromMap(tops);
  frame.ModelFromMap(bottoms);
  std::vector<RayHit> hits(n);
  ParallelFor(static_cast<std::size_t>(cells.height), num_threads, [&](std::size_t r) {
    for (int c = 0; c < cells.width; ++c) {
      const std::size_t i = r * cells.width + c;
      RayHit hit = scene.Intersect(tops[i], bottoms[i] - tops[i]);  // distance in units of the ray's length
      if (!hit.hit || hit.distance > 1.0) hit = RayHit();
      hits[i] = hit;
    }
  });
  return hits;
}

Eigen::Vector3d SurfacePoint(const Mesh& mesh, std::uint32_t face, double b1, double b2) {
  const Mesh::Face& corners = mesh.faces[face];
  return (1.0 - b1 - b2) * mesh.vertices[corners[0]] + b1 * mesh.vertices[corners[1]] + b2 * mesh.vertices[corners[2]];
}

}  // namespace

OrthoGrid OrthoGridOfMesh(const Mesh& mesh, const MapFrame& frame, double gsd) {
  if (!(gsd > 0.0) || !std::isfinite(gsd)) {
    throw std::invalid_argument("the GSD must be a positive number of metres per pixel");
  }
  if (mesh.vertices.empty()) throw std::invalid_argument("the mesh has no vertices");
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  constexpr std::size_t kBatch = 1 << 16;
  std::vector<Eigen::Vector3d> batch;
  for (std::size_t first = 0; first < mesh.vertices.size(); first += kBatch) {
    const std::size_t last = std::min(mesh.vertices.size(), first + kBatch);
    batch.assign(mesh.vertices.begin() + static_cast<std::ptrdiff_t>(first),
                 mesh.vertices.begin() + static_cast<std::ptrdiff_t>(last));
    frame.MapFromModel(batch);
    for (const Eigen::Vector3d& point : batch) {
      low = low.cwiseMin(point);
      high = high.cwiseMax(point);
    }
  }
  OrthoGrid grid;
  grid.bottom = low.z();
  grid.top = high.z();
  GeoRasterGrid& raster = grid.raster;
  raster.gsd = gsd;
  // A bound that is a multiple of the GSD up to rounding stays on that multiple.
  raster.west = std::floor(low.x() / gsd + 1e-6) * gsd;
  raster.north = std::ceil(high.y() / gsd - 1e-6) * gsd;
  const double width = std::ceil((high.x() - raster.west) / gsd);
  const double height = std::ceil((raster.north - low.y()) / gsd);
  if (width * height > kMaxOrthoCells || width > 1e6 || height > 1e6) {
    std::ostringstream message;
    message << "a GSD of " << gsd << " m would make a mosaic of " << std::fixed << std::setprecision(0) << width
            << " x " << height << " pixels (" << std::scientific << std::setprecision(1) << width * height
            << ") over " << std::fixed << high.x() - low.x() << " x " << high.y() - low.y() << " m; the limit is "
            << std::scientific << kMaxOrthoCells << " pixels: choose a coarser GSD";
    throw std::invalid_argument(message.str());
  }
  raster.width = std::max(1, static_cast<int>(width));
  raster.height = std::max(1, static_cast<int>(height));
  raster.crs_wkt = frame.crs_wkt();
  return grid;
}

void CheckSurfaceFromAbove(const RaycastScene& scene, const MapFrame& frame, const OrthoGrid& grid, int num_threads) {
  const int probe = 64;
  std::size_t hits = 0;
  for (int r = 0; r < probe; ++r) {
    const int row = static_cast<int>((r + 0.5) * grid.raster.height / probe);
    for (const RayHit& hit : CastCellsDown(scene, frame, grid, cv::Rect(0, row, grid.raster.width, 1), num_threads)) {
      hits += hit.face_id >= 0;
    }
  }
  if (hits == 0) throw std::invalid_argument("the mesh has no surface seen from above (no ray cast down hits it)");
}

void OrthoMosaicOptions::Check() const {
  baking.Check();
  if (tile_size < 16 || tile_size > 8192) throw std::invalid_argument("the tile size must be 16 to 8192 cells");
}

OrthoMosaicSummary MakeOrthoMosaic(const Mesh& mesh, const RaycastScene& scene, const std::vector<TextureView>& views,
                                   const ViewImageSource& source, const MapFrame& frame, const OrthoGrid& grid,
                                   const OrthoMosaicOptions& options,
                                   const std::function<void(const OrthoTile&)>& write_tile) {
  options.Check();
  if (views.empty()) throw std::invalid_argument("mosaic: no views");
  const GeoRasterGrid& raster = grid.raster;
  const int num_threads = options.baking.num_threads;
  CheckSurfaceFromAbove(scene, frame, grid, num_threads);
  OrthoMosaicSummary summary;
  summary.num_views = views.size();
  summary.num_cells = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height);

  auto start = std::chrono::steady_clock::now();
  const ViewRaycaster raycaster(scene);
  const ChosenViews chosen = ChooseViews(mesh, FaceAdjacency(mesh), views, raycaster, source, options.baking);
  const FaceViewCandidates& candidates = chosen.candidates;
  const std::vector<std::uint32_t>& view_of_face = chosen.selection.view_of_face;
  summary.levelling = chosen.levelling;
  summary.seconds_selection = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  TexelFusionOptions fusion = options.baking.fusion;
  fusion.num_threads = num_threads;
  fusion.show_progress = false;
  TexelLayout layout;
  layout.face_ranges.assign(mesh.faces.size(), {0, 0});
  const int tiles_x = (raster.width + options.tile_size - 1) / options.tile_size;
  const int tiles_y = (raster.height + options.tile_size - 1) / options.tile_size;
  summary.num_tiles = static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y);
  ProgressReporter progress("mosaic", summary.num_tiles, "tiles");
  double samples = 0.0;
  for (int ty = 0; ty < tiles_y; ++ty) {
    for (int tx = 0; tx < tiles_x; ++tx) {
      const cv::Rect cells(tx * options.tile_size, ty * options.tile_size,
                           std::min(options.tile_size, raster.width - tx * options.tile_size),
                           std::min(options.tile_size, raster.height - ty * options.tile_size));
      const std::vector<RayHit> hits = CastCellsDown(scene, frame, grid, cells, num_threads);
      // The tile's texels, face by face (the fusion's layout), then the faces' ranges.
      layout.texels.clear();
      for (int r = 0; r < cells.height; ++r) {
        for (int c = 0; c < cells.width; ++c) {
          const RayHit& hit = hits[static_cast<std::size_t>(r) * cells.width + c];
          if (hit.face_id < 0) continue;
          AtlasTexel texel;
          texel.face = static_cast<std::uint32_t>(hit.face_id);
          texel.x = static_cast<std::uint16_t>(c);
          texel.y = static_cast<std::uint16_t>(r);
          texel.b1 = hit.b1;
          texel.b2 = hit.b2;
          layout.texels.push_back(texel);
        }
      }
      std::stable_sort(layout.texels.begin(), layout.texels.end(),
                       [](const AtlasTexel& a, const AtlasTexel& b) { return a.face < b.face; });
      for (std::size_t t = 0; t < layout.texels.size();) {
        std::size_t end = t;
        while (end < layout.texels.size() && layout.texels[end].face == layout.texels[t].face) ++end;
        layout.face_ranges[layout.texels[t].face] = {t, end};
        t = end;
      }
      layout.chart_offsets = {0, layout.texels.size()};
      OrthoTile tile;
      tile.col = cells.x;
      tile.row = cells.y;
      std::vector<cv::Mat> pages{
          cv::Mat(cells.size(), CV_32FC3, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()))};
      tile.height = cv::Mat(cells.size(), CV_32FC1, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
      if (!layout.texels.empty()) {
        const TexelFusionSummary fused =
            FuseTexels(mesh, views, raycaster, source, candidates, view_of_face, layout, fusion, pages);
        ApplySeamCorrections(mesh, view_of_face, chosen.corrections, /*source_vertex=*/{}, layout, num_threads, pages);
        summary.tile_view_reads += fused.views_read;
        samples += fused.mean_samples_per_texel * double(fused.num_texels);
        std::vector<Eigen::Vector3d> points(layout.texels.size());
        for (std::size_t t = 0; t < points.size(); ++t) {
          points[t] = SurfacePoint(mesh, layout.texels[t].face, layout.texels[t].b1, layout.texels[t].b2);
        }
        frame.MapFromModel(points);
        for (std::size_t t = 0; t < points.size(); ++t) {
          tile.height.at<float>(layout.texels[t].y, layout.texels[t].x) = static_cast<float>(points[t].z());
          layout.face_ranges[layout.texels[t].face] = {0, 0};
        }
      }
      tile.colour = pages[0];
      summary.surface_cells += layout.texels.size();
      for (const AtlasTexel& texel : layout.texels) {
        summary.seen_cells += std::isfinite(tile.colour.at<cv::Vec3f>(texel.y, texel.x)[0]);
      }
      write_tile(tile);
      progress.Advance();
    }
  }
  progress.Finish();
  summary.mean_samples_per_cell = summary.surface_cells ? samples / double(summary.surface_cells) : 0.0;
  summary.seconds_tiles = SecondsSince(start);
  return summary;
}

}  // namespace lutex
