// The orthomosaic made tile by tile on the tiles' pieces of the mesh (texturing/ortho_mosaic.h), against
// the truth and against the same mosaic made as one tile: a seafloor with a boulder, seen by nine views
// that disagree by a few percent in brightness (as restored images of a dive do), mapped at 1 cm in tiles
// of 32 cells, so that tile borders run everywhere, over the boulder's flanks too.

#include "texturing/ortho_mosaic.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/rendered_views.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

struct Scene {
  Mesh mesh = BoulderFloor();
  std::vector<TextureView> views = NineViewsOfTheCentre(Camera::Pinhole(1, 320, 240, 250.0, 250.0));
  std::vector<cv::Mat> images;
  ViewImageSource source;

  Scene() {
    const RaycastScene scene(mesh);
    for (std::size_t v = 0; v < views.size(); ++v) {
      images.push_back(RenderPatchwork(scene, views[v]) * (1.0 + 0.12 * std::sin(2.0 * double(v) + 0.5)));
    }
    source.linear_rgb = [this](std::size_t v, const cv::Rect& window) { return ViewWindow(images[v], window); };
  }
};

struct Mosaic {
  cv::Mat colour;  // CV_32FC3, NaN where nodata
  cv::Mat height;  // CV_32FC1
  OrthoMosaicSummary summary;
};

// Tiles of `tile_size` cells in blocks of `block_side` tiles a side.
Mosaic MakeMosaic(const Scene& scene, const MapFrame& frame, const OrthoGrid& grid, int tile_size, int block_side,
                  TexelBlend blend) {
  const OrthoTiling tiling = TileOrthoGrid(scene.mesh, frame, grid, tile_size, block_side);
  OrthoMosaicOptions options;
  options.tile_size = tile_size;
  options.baking.fusion.blend = blend;
  options.baking.num_threads = 2;
  Mosaic mosaic;
  mosaic.colour = cv::Mat(grid.raster.height, grid.raster.width, CV_32FC3, cv::Scalar::all(-1.0));
  mosaic.height = cv::Mat(grid.raster.height, grid.raster.width, CV_32FC1, cv::Scalar::all(-1.0));
  const auto keep = [&](const OrthoTile& tile) {
    const cv::Rect cells(tile.col, tile.row, tile.colour.cols, tile.colour.rows);
    tile.colour.copyTo(mosaic.colour(cells));
    tile.height.copyTo(mosaic.height(cells));
  };
  const testing::TempDir scratch;
  mosaic.summary =
      MakeOrthoMosaic(scene.mesh, scene.views, scene.source, frame, grid, options, keep, scratch.path() / "mesh", &tiling);
  return mosaic;
}

// Whether the patchwork is one colour within 2 cm of the centre of cell (col, row) (the mosaic's sampling
// blurs its edges).
bool AwayFromPatchEdges(const OrthoGrid& grid, int col, int row) {
  const Eigen::Vector3d point(grid.raster.west + (col + 0.5) * grid.raster.gsd,
                              grid.raster.north - (row + 0.5) * grid.raster.gsd, 0.0);
  const Eigen::Vector3f truth = PatchworkAlbedo(point);
  for (const Eigen::Vector3d& offset : {Eigen::Vector3d(0.02, 0, 0), Eigen::Vector3d(-0.02, 0, 0),
                                        Eigen::Vector3d(0, 0.02, 0), Eigen::Vector3d(0, -0.02, 0)}) {
    if (PatchworkAlbedo(point + offset) != truth) return false;
  }
  return true;
}

// Mean |difference| over channels between horizontally or vertically neighbouring cells that both have a
// colour, away from the patches' edges, for the pairs that cross a border between tiles of `tile_size`
// (`across`) or not; percentage points.
double NeighbourStep(const OrthoGrid& grid, const cv::Mat& colour, int tile_size, bool across) {
  double sum = 0.0;
  std::size_t n = 0;
  for (int row = 0; row < colour.rows; ++row) {
    for (int col = 0; col < colour.cols; ++col) {
      if (!AwayFromPatchEdges(grid, col, row)) continue;
      for (const cv::Point next : {cv::Point(col + 1, row), cv::Point(col, row + 1)}) {
        if (next.x >= colour.cols || next.y >= colour.rows) continue;
        const bool crosses = next.x != col ? next.x % tile_size == 0 : next.y % tile_size == 0;
        if (crosses != across) continue;
        const cv::Vec3f a = colour.at<cv::Vec3f>(row, col), b = colour.at<cv::Vec3f>(next);
        if (!std::isfinite(a[0]) || !std::isfinite(b[0])) continue;
        sum += (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2])) / 3.0;
        ++n;
      }
    }
  }
  return 100.0 * sum / double(n);
}

// Tiles of 32 cells map the surface the one tile maps, to the same heights, as truly, and show no step
// where they meet: a face that the cells of two tiles show has one label and one seam correction.
TEST(OrthoMosaic, TilesOfAFewCellsMapTheSurfaceAsOneTileDoesWithoutStepsAtTheirBorders) {
  const Scene scene;
  const MapFrame frame{Georeference()};
  const OrthoGrid grid = OrthoGridOfMesh(scene.mesh, frame, 0.01);
  constexpr int kSmallTile = 32;
  // Blocks of one tile, and of 3 x 3 (the last of a row or column cut at the grid's edge).
  for (const auto& [blend, block_side] : {std::pair(TexelBlend::kFuse, 1), std::pair(TexelBlend::kSingle, 1),
                                          std::pair(TexelBlend::kSingle, 3)}) {
    SCOPED_TRACE((blend == TexelBlend::kFuse ? "fuse, blocks of " : "single, blocks of ") + std::to_string(block_side));
    const Mosaic tiled = MakeMosaic(scene, frame, grid, kSmallTile, block_side, blend);
    const Mosaic whole = MakeMosaic(scene, frame, grid, 256, 1, blend);
    ASSERT_EQ(whole.summary.num_tiles, 1u);
    ASSERT_GT(tiled.summary.num_tiles, 40u);
    EXPECT_EQ(tiled.summary.num_blocks, block_side == 1 ? tiled.summary.num_tiles : 9u);
    EXPECT_EQ(tiled.summary.surface_cells, whole.summary.surface_cells);
    EXPECT_NEAR(double(tiled.summary.seen_cells), double(whole.summary.seen_cells),
                1e-4 * double(whole.summary.seen_cells));
    EXPECT_GT(tiled.summary.seen_cells, tiled.summary.num_cells * 9 / 10);
    EXPECT_LT(tiled.summary.max_piece_faces, scene.mesh.faces.size()) << "each tile works on a piece";

    // Heights: the same surface points, and those of the mesh's height field.
    double worst_height = 0.0;
    for (int row = 0; row < grid.raster.height; ++row) {
      for (int col = 0; col < grid.raster.width; ++col) {
        worst_height = std::max(worst_height, double(std::abs(tiled.height.at<float>(row, col) -
                                                                  whole.height.at<float>(row, col))));
      }
    }
    EXPECT_LT(worst_height, 1e-5);

    // Colour against the patchwork at each cell's surface point (away from the patches' edges).
    const auto error = [&](const Mosaic& mosaic) {
      double sum = 0.0;
      std::size_t n = 0;
      for (int row = 0; row < grid.raster.height; ++row) {
        for (int col = 0; col < grid.raster.width; ++col) {
          const cv::Vec3f c = mosaic.colour.at<cv::Vec3f>(row, col);
          if (!std::isfinite(c[0]) || !AwayFromPatchEdges(grid, col, row)) continue;
          const Eigen::Vector3f truth = PatchworkAlbedo({grid.raster.west + (col + 0.5) * grid.raster.gsd,
                                                         grid.raster.north - (row + 0.5) * grid.raster.gsd, 0.0});
          sum += (std::abs(c[0] - truth.x()) + std::abs(c[1] - truth.y()) + std::abs(c[2] - truth.z())) / 3.0;
          ++n;
        }
      }
      return 100.0 * sum / double(n);
    };
    const double error_tiled = error(tiled), error_whole = error(whole);
    const double across = NeighbourStep(grid, tiled.colour, kSmallTile, true);
    const double inside = NeighbourStep(grid, tiled.colour, kSmallTile, false);
    const double across_whole = NeighbourStep(grid, whole.colour, kSmallTile, true);
    std::cout << (blend == TexelBlend::kFuse ? "fused" : "one view per face") << " mosaic in "
              << tiled.summary.num_tiles << " tiles, " << tiled.summary.num_blocks << " blocks (pieces of at most " << tiled.summary.max_piece_faces << " of "
              << scene.mesh.faces.size() << " faces): mae " << error_tiled << " pp (one tile: " << error_whole
              << "); step between neighbouring cells across tile borders " << across << " pp, inside tiles " << inside
              << " (one tile, the same pairs: " << across_whole << ")\n";
    EXPECT_LT(error_tiled, 3.0);  // the views are up to 12 % too bright or dark
    // Each block is chosen and levelled with the blocks before it held: a little less free than one tile
    // (one view per face: 1.79 pp in blocks of one tile, 1.87 in blocks of 3 x 3, against 1.67).
    EXPECT_LT(error_tiled, error_whole * 1.15 + 0.05);
    // The tiles' borders add no step to what the same cell pairs show in one tile (fusing: face edges
    // where the views change run along some of the borders). One view per face shows each label and
    // correction as it is: there a face shown by two tiles with the corrections of its corners settled
    // only where it meets the later tile's faces added 0.78 pp (measured); settled at all its corners,
    // less than 0.01.
    EXPECT_LT(across - across_whole, 0.05);
  }
}

// A block of tiles spans about one image's footprint: a flat floor seen from 2 m by images 320 pixels wide
// at a focal length of 250 pixels is 2.56 m wide in each image.
TEST(OrthoMosaic, ABlockOfTilesSpansAboutAnImagesFootprint) {
  const Mesh floor = MakeHeightFieldMesh([](double, double) { return 0.0; }, -3.0, 3.0, -3.0, 3.0, 12, 12);
  std::vector<TextureView> views;
  for (double x : {-1.0, 0.0, 1.0}) {
    views.push_back({"view", Camera::Pinhole(1, 320, 240, 250.0, 250.0),
                     CamFromWorldLookingAt(Eigen::Vector3d(x, 0.0, 2.0), -Eigen::Vector3d::UnitZ(),
                                           Eigen::Vector3d::UnitY())});
  }
  const MapFrame frame{Georeference()};
  const OrthoGrid grid = OrthoGridOfMesh(floor, frame, 0.01);
  const std::vector<double> gsds = GsdsAtImageCentres(floor, views);
  EXPECT_EQ(OrthoBlockSide(gsds, views, grid, 64), 4);   // 2.56 m of 0.64 m tiles
  EXPECT_EQ(OrthoBlockSide(gsds, views, grid, 128), 2);  // of 1.28 m tiles
  EXPECT_EQ(OrthoBlockSide(gsds, views, grid, 512), 1);  // a tile wider than an image's footprint
  EXPECT_EQ(OrthoBlockSide(gsds, views, grid, 16), 16);  // of 0.16 m tiles
  // At most 8192 cells a side: at 0.1 mm, 400 tiles of 64 cells would span a footprint.
  EXPECT_EQ(OrthoBlockSide(gsds, views, OrthoGridOfMesh(floor, frame, 1e-4), 64), 128);
  // No image centre on the mesh: blocks of one tile.
  for (TextureView& view : views) view.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.0, 0.0, 2.0),
                                                                               Eigen::Vector3d::UnitZ(),
                                                                               Eigen::Vector3d::UnitY());
  EXPECT_EQ(OrthoBlockSide(GsdsAtImageCentres(floor, views), views, grid, 64), 1);
  EXPECT_THROW(OrthoBlockSide({0.01}, views, grid, 64), std::invalid_argument);  // not one GSD per view
}

}  // namespace
}  // namespace lutex
