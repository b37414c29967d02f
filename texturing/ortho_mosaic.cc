#include "texturing/ortho_mosaic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "lib/raycast/few_ray_hits.h"
#include "lib/util/median.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"
#include "texturing/texel_fusion.h"
#include "texturing/texel_layout.h"
#include "texturing/tile_views.h"

namespace lutex {

namespace {

// A face is seen from above when its normal is at least this far from horizontal (the cosine).
constexpr double kMinSeenFromAbove = 1e-6;
// Most cells a side of a block (64 Mpixels): bounds the block when the GSD is far finer than the images'.
constexpr int kMaxBlockCells = 8192;

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

void CheckSurfaceFromAbove(const Mesh& mesh, const MapFrame& frame) {
  if (mesh.faces.empty()) throw std::invalid_argument("the mesh has no faces");
  // The map's vertical in the model's frame, at the mesh's centre (it turns by well under a degree over a survey).
  const Eigen::Vector3d centre_in_map = frame.MapFromModel(0.5 * (mesh.BoundsMin() + mesh.BoundsMax()));
  const Eigen::Vector3d up_in_model = (frame.ModelFromMap(centre_in_map + Eigen::Vector3d::UnitZ()) -
                                       frame.ModelFromMap(centre_in_map)).normalized();
  for (const Mesh::Face& face : mesh.faces) {
    const Eigen::Vector3d normal = (mesh.vertices[face[1]] - mesh.vertices[face[0]])
                                       .cross(mesh.vertices[face[2]] - mesh.vertices[face[0]]);
    const double norm = normal.norm();
    if (norm > 0.0 && std::abs(normal.dot(up_in_model)) > kMinSeenFromAbove * norm) return;
  }
  throw std::invalid_argument("the mesh has no surface seen from above (every face is vertical or degenerate)");
}

cv::Rect OrthoTiling::BlockCells(std::size_t block, const GeoRasterGrid& raster) const {
  const int bx = static_cast<int>(block % static_cast<std::size_t>(blocks_x));
  const int by = static_cast<int>(block / static_cast<std::size_t>(blocks_x));
  const int side = block_side * tile_size;
  return cv::Rect(bx * side, by * side, std::min(side, raster.width - bx * side),
                  std::min(side, raster.height - by * side));
}

std::vector<cv::Rect> OrthoTiling::TilesOfBlock(std::size_t block, const GeoRasterGrid& raster) const {
  const cv::Rect cells = BlockCells(block, raster);
  std::vector<cv::Rect> tiles;
  for (int y = cells.y; y < cells.y + cells.height; y += tile_size) {
    for (int x = cells.x; x < cells.x + cells.width; x += tile_size) {
      tiles.emplace_back(x, y, std::min(tile_size, raster.width - x), std::min(tile_size, raster.height - y));
    }
  }
  return tiles;
}

std::size_t OrthoTiling::MostFaces() const {
  std::size_t most = 0;
  for (const std::vector<std::uint32_t>& block : faces) most = std::max(most, block.size());
  return most;
}

std::vector<double> GsdsAtImageCentres(const Mesh& mesh, const std::vector<TextureView>& views) {
  std::vector<Ray3d> centres;
  for (const TextureView& view : views) {
    centres.push_back({view.cam_from_world.TargetOriginInSource(),
                       view.cam_from_world.rotation.inverse() * Eigen::Vector3d::UnitZ()});
  }
  std::vector<double> gsds = FirstHitDistances(mesh, centres);
  for (std::size_t v = 0; v < views.size(); ++v) {
    gsds[v] /= 0.5 * (views[v].camera.FocalLengthX() + views[v].camera.FocalLengthY());
  }
  return gsds;
}

int OrthoBlockSide(const std::vector<double>& gsds, const std::vector<TextureView>& views, const OrthoGrid& grid,
                   int tile_size) {
  if (gsds.size() != views.size()) throw std::invalid_argument("block side: one GSD per view");
  std::vector<double> footprints;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Camera& camera = views[v].camera;
    if (std::isfinite(gsds[v])) footprints.push_back(gsds[v] * double(std::max(camera.width, camera.height)));
  }
  if (footprints.empty()) return 1;
  const double tile_metres = tile_size * grid.raster.gsd;
  const int most = std::max(1, kMaxBlockCells / tile_size);
  return std::clamp(static_cast<int>(std::lround(MedianInPlace(footprints) / tile_metres)), 1, most);
}

OrthoTiling TileOrthoGrid(const Mesh& mesh, const MapFrame& frame, const OrthoGrid& grid, int tile_size,
                          int block_side) {
  if (tile_size < 1 || block_side < 1) throw std::invalid_argument("the tiles and blocks must have a positive size");
  const GeoRasterGrid& raster = grid.raster;
  OrthoTiling tiling;
  tiling.tile_size = tile_size;
  tiling.tiles_x = (raster.width + tile_size - 1) / tile_size;
  tiling.tiles_y = (raster.height + tile_size - 1) / tile_size;
  tiling.block_side = block_side;
  tiling.blocks_x = (tiling.tiles_x + block_side - 1) / block_side;
  tiling.blocks_y = (tiling.tiles_y + block_side - 1) / block_side;
  const int block_cells = block_side * tile_size;
  tiling.faces.resize(static_cast<std::size_t>(tiling.blocks_x) * static_cast<std::size_t>(tiling.blocks_y));
  constexpr std::size_t kBatch = 1 << 16;
  std::vector<Eigen::Vector3d> centroids;
  for (std::size_t first = 0; first < mesh.faces.size(); first += kBatch) {
    const std::size_t last = std::min(mesh.faces.size(), first + kBatch);
    centroids.clear();
    for (std::size_t f = first; f < last; ++f) {
      const Mesh::Face& face = mesh.faces[f];
      centroids.push_back((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0);
    }
    frame.MapFromModel(centroids);
    for (std::size_t f = first; f < last; ++f) {
      const Eigen::Vector3d& point = centroids[f - first];
      const int col =
          std::clamp(static_cast<int>(std::floor((point.x() - raster.west) / raster.gsd)), 0, raster.width - 1);
      const int row =
          std::clamp(static_cast<int>(std::floor((raster.north - point.y()) / raster.gsd)), 0, raster.height - 1);
      tiling.faces[static_cast<std::size_t>(row / block_cells) * tiling.blocks_x + col / block_cells].push_back(
          static_cast<std::uint32_t>(f));
    }
  }
  return tiling;
}

void OrthoMosaicOptions::Check() const {
  baking.Check();
  if (tile_size < 16 || tile_size > 8192) throw std::invalid_argument("the tile size must be 16 to 8192 cells");
}

OrthoMosaicSummary MakeOrthoMosaic(const Mesh& mesh, const std::vector<TextureView>& views,
                                   const ViewImageSource& source, const MapFrame& frame, const OrthoGrid& grid,
                                   const OrthoMosaicOptions& options,
                                   const std::function<void(const OrthoTile&)>& write_tile,
                                   const std::filesystem::path& scratch, const OrthoTiling* tiling,
                                   const std::function<void()>& mesh_on_disk) {
  const auto start = std::chrono::steady_clock::now();
  options.Check();
  if (views.empty()) throw std::invalid_argument("mosaic: no views");
  CheckSurfaceFromAbove(mesh, frame);
  const GeoRasterGrid& raster = grid.raster;
  const int num_threads = options.baking.num_threads;
  OrthoMosaicSummary summary;
  summary.num_views = views.size();
  summary.num_cells = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height);
  OrthoTiling made_here;
  if (!tiling) {
    made_here =
        TileOrthoGrid(mesh, frame, grid, options.tile_size,
                      OrthoBlockSide(GsdsAtImageCentres(mesh, views), views, grid, options.tile_size));
    tiling = &made_here;
  } else if (tiling->tile_size != options.tile_size) {
    throw std::invalid_argument("mosaic: the tiling is not of the options' tile size");
  }
  summary.num_tiles = tiling->num_tiles();
  summary.num_blocks = tiling->num_blocks();

  // Each block spans the column over its cells.
  std::vector<Eigen::AlignedBox3d> spans(tiling->num_blocks());
  std::vector<const std::vector<std::uint32_t>*> blocks(tiling->num_blocks());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const cv::Rect cells = tiling->BlockCells(b, raster);
    std::vector<Eigen::Vector3d> corners;
    for (int corner = 0; corner < 8; ++corner) {
      corners.emplace_back(raster.west + (corner & 1 ? cells.x + cells.width : cells.x) * raster.gsd,
                           raster.north - (corner & 2 ? cells.y + cells.height : cells.y) * raster.gsd,
                           corner & 4 ? grid.top : grid.bottom);
    }
    frame.ModelFromMap(corners);
    for (const Eigen::Vector3d& corner : corners) spans[b].extend(corner);
    blocks[b] = &tiling->faces[b];
  }
  TiledViewChoice choice(mesh, views, blocks, options.baking, scratch, spans);
  if (mesh_on_disk) mesh_on_disk();

  TexelFusionOptions fusion = options.baking.fusion;
  fusion.num_threads = num_threads;
  fusion.show_progress = false;
  ProgressReporter progress("mosaic", summary.num_tiles, "tiles");
  double samples = 0.0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const cv::Rect block_cells = tiling->BlockCells(b, raster);
    const std::vector<cv::Rect> tile_cells = tiling->TilesOfBlock(b, raster);
    // The block's piece holds every face over its cells. The faces its cells may show are those whose
    // footprint in the map reaches them; they are chosen with the block's unless a block before chose
    // them. A face reaching beyond the block's cells may be shown by a later block too.
    // Its edges in the map, by the expressions its neighbours' edges use.
    const double west = raster.west + block_cells.x * raster.gsd;
    const double east = raster.west + (block_cells.x + block_cells.width) * raster.gsd;
    const double north = raster.north - block_cells.y * raster.gsd;
    const double south = raster.north - (block_cells.y + block_cells.height) * raster.gsd;
    std::vector<Eigen::AlignedBox2d> footprints;  // of the piece's faces, in the map
    TileUse use;
    use.shown = [&](const TileMesh& piece) {
      std::vector<Eigen::Vector3d> vertices_in_map = piece.mesh.vertices;
      frame.MapFromModel(vertices_in_map);
      const Eigen::AlignedBox2d cells(Eigen::Vector2d(west, south), Eigen::Vector2d(east, north));
      std::vector<std::uint32_t> shown;
      footprints.resize(piece.mesh.faces.size());
      for (std::size_t f = 0; f < piece.mesh.faces.size(); ++f) {
        footprints[f].setEmpty();
        for (std::uint32_t v : piece.mesh.faces[f]) footprints[f].extend(vertices_in_map[v].head<2>());
        if (footprints[f].intersects(cells)) shown.push_back(static_cast<std::uint32_t>(f));
      }
      return shown;
    };
    // Reaching a neighbour's cells, or touching its edge (which its `shown` counts).
    use.shown_later = [&](std::uint32_t face) {
      const Eigen::AlignedBox2d& footprint = footprints[face];
      return footprint.min().x() <= west || footprint.max().x() >= east || footprint.min().y() <= south ||
             footprint.max().y() >= north;
    };
    const TilePiece piece = choice.Choose(b, source, &use);
    footprints = {};

    for (const cv::Rect& cells : tile_cells) {
      OrthoTile tile;
      tile.col = cells.x;
      tile.row = cells.y;
      std::vector<cv::Mat> pages{
          cv::Mat(cells.size(), CV_32FC3, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()))};
      tile.height = cv::Mat(cells.size(), CV_32FC1, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
      // The tile's texels, face by face (the fusion's layout), then the faces' ranges.
      TexelLayout layout;
      if (piece.scene) {
        const std::vector<RayHit> hits = CastCellsDown(*piece.scene, frame, grid, cells, num_threads);
        for (std::size_t i = 0; i < hits.size(); ++i) {
          const RayHit& hit = hits[i];
          if (hit.face_id < 0) continue;
          AtlasTexel texel;
          texel.face = static_cast<std::uint32_t>(hit.face_id);
          texel.x = static_cast<std::uint16_t>(i % static_cast<std::size_t>(cells.width));
          texel.y = static_cast<std::uint16_t>(i / static_cast<std::size_t>(cells.width));
          texel.b1 = hit.b1;
          texel.b2 = hit.b2;
          layout.texels.push_back(texel);
        }
      }
      if (!layout.texels.empty()) {
        const Mesh& piece_mesh = piece.piece.mesh;
        std::stable_sort(layout.texels.begin(), layout.texels.end(),
                         [](const AtlasTexel& x, const AtlasTexel& y) { return x.face < y.face; });
        layout.face_ranges.assign(piece_mesh.faces.size(), {0, 0});
        for (std::size_t i = 0; i < layout.texels.size();) {
          std::size_t end = i;
          while (end < layout.texels.size() && layout.texels[end].face == layout.texels[i].face) ++end;
          layout.face_ranges[layout.texels[i].face] = {i, end};
          i = end;
        }
        layout.chart_offsets = {0, layout.texels.size()};
        const std::vector<std::uint32_t>& view_of_face = piece.chosen.selection.view_of_face;
        const TexelFusionSummary fused = FuseTexels(piece_mesh, views, *piece.raycaster, source,
                                                    piece.chosen.candidates, view_of_face, layout, fusion, pages);
        ApplySeamCorrections(piece_mesh, view_of_face, piece.chosen.corrections, /*source_vertex=*/{}, layout,
                             num_threads, pages);
        summary.tile_view_reads += fused.views_read;
        samples += fused.mean_samples_per_texel * double(fused.num_texels);
        std::vector<Eigen::Vector3d> points(layout.texels.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
          points[i] = SurfacePoint(piece_mesh, layout.texels[i].face, layout.texels[i].b1, layout.texels[i].b2);
        }
        frame.MapFromModel(points);
        for (std::size_t i = 0; i < points.size(); ++i) {
          tile.height.at<float>(layout.texels[i].y, layout.texels[i].x) = static_cast<float>(points[i].z());
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
  summary.levelling = choice.levelling();
  summary.seconds_selection = choice.seconds();
  summary.seconds_tiles = SecondsSince(start) - summary.seconds_selection;
  summary.max_piece_faces = choice.max_piece_faces();
  return summary;
}

}  // namespace lutex
