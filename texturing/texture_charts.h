#pragma once

// Charts: groups of faces textured from the same view, laid out in texel space by projecting them into
// that view. A projection into the view that sees the faces never folds them over each other (they are
// visible, so front-facing and unoccluded), and keeps the view's pixel grid, so a texel of a chart maps
// onto the view's pixels with almost no resampling.
//
// Texel size: with `texel_size` > 0 (scene units, e.g. 0.001 for 1 mm), each chart's projection is
// scaled so that one texel covers `texel_size` on the surface at the chart's median depth, whatever the
// range the view was taken from; with 0, one texel is one pixel of the view (native resolution).
//
// A chart larger than a page (less its padding) is cut into tiles, each a chart of its own.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/mesh.h"
#include "texturing/face_adjacency.h"
#include "texturing/texture_views.h"

namespace lutex {

struct TextureChart {
  std::uint32_t view = 0;
  std::vector<std::uint32_t> faces;
  // Texel coordinates of the corners of each face (3 per face, in `faces` order) inside the chart's
  // rectangle: x right, y down, the centre of texel (i, j) at (i + 0.5, j + 0.5); `padding` texels of
  // margin on every side.
  std::vector<Eigen::Vector2f> corner_texels;
  int width = 0;
  int height = 0;
};

struct TextureChartOptions {
  // Scene units per texel; 0 = native resolution of each chart's view.
  double texel_size = 0.0;
  // Empty texels around each chart, filled by dilation so that filtering and mip-mapping near a chart's
  // border never reach another chart's colours.
  int padding = 4;
  // Largest chart rectangle (the atlas page size).
  int max_size = 8192;
  void Check() const;
};

// Charts of the faces whose `view_of_face` is not kNoView: connected components (shared edges) of one
// view. Deterministic: charts in order of their smallest face, faces ascending; the tiles of a chart cut
// to fit a page take its place, one after the other in their order in the view.
std::vector<TextureChart> BuildTextureCharts(const Mesh& mesh, const FaceAdjacency& adjacency,
                                             const std::vector<TextureView>& views,
                                             const std::vector<std::uint32_t>& view_of_face,
                                             const TextureChartOptions& options);

}  // namespace lutex
