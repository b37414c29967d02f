// The texels of hand-made charts whose triangles are known exactly (a square of two triangles), and of
// the charts of a flat floor seen straight down, where a texel is a pixel of the view and its surface
// point must project back onto the texel's centre.

#include "texturing/texel_layout.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "texturing/face_adjacency.h"

namespace lutex {
namespace {

// A chart of two triangles covering the square [4, 20]^2 (texel units) of a 24 x 24 rectangle: `lower`
// is (4,4) (20,4) (20,20), the triangle below the diagonal in texel rows (x > y); `upper` is
// (4,4) (20,20) (4,20).
TextureChart SquareChart(std::uint32_t lower, std::uint32_t upper) {
  TextureChart chart;
  chart.faces = {lower, upper};
  chart.corner_texels = {{4, 4}, {20, 4}, {20, 20}, {4, 4}, {20, 20}, {4, 20}};
  chart.width = 24;
  chart.height = 24;
  return chart;
}

// The point of the chart (texel units) that a texel shows.
Eigen::Vector2d ChartPoint(const TextureChart& chart, std::size_t face_index, const AtlasTexel& texel) {
  const Eigen::Vector2d p0 = chart.corner_texels[3 * face_index].cast<double>();
  const Eigen::Vector2d p1 = chart.corner_texels[3 * face_index + 1].cast<double>();
  const Eigen::Vector2d p2 = chart.corner_texels[3 * face_index + 2].cast<double>();
  return (1.0 - texel.b1 - texel.b2) * p0 + double(texel.b1) * p1 + double(texel.b2) * p2;
}

std::size_t FaceIndexInChart(const TextureChart& chart, std::uint32_t face) {
  return static_cast<std::size_t>(std::find(chart.faces.begin(), chart.faces.end(), face) - chart.faces.begin());
}

bool OnTriangle(const AtlasTexel& texel, float tolerance = 1e-5f) {
  return texel.b1 >= -tolerance && texel.b2 >= -tolerance && texel.b1 + texel.b2 <= 1.0f + tolerance;
}

// Distance from q to the square [4, 20]^2.
double DistanceToSquare(const Eigen::Vector2d& q) {
  const Eigen::Vector2d nearest = q.cwiseMax(Eigen::Vector2d::Constant(4.0)).cwiseMin(Eigen::Vector2d::Constant(20.0));
  return (q - nearest).norm();
}

// Face ranges and chart offsets consistent with the texels: each face's texels one contiguous range,
// ranges in the chart's face order tiling the chart's range, every texel in its chart's placement, no
// texel of a page twice. With `overlapping_faces` a face may have no texels (an earlier face of its chart
// covers it).
void ExpectConsistentLayout(const TexelLayout& layout, const std::vector<TextureChart>& charts, const AtlasLayout& atlas,
                            std::size_t num_faces, bool overlapping_faces = false) {
  ASSERT_EQ(layout.face_ranges.size(), num_faces);
  ASSERT_EQ(layout.chart_offsets.size(), charts.size() + 1);
  EXPECT_EQ(layout.chart_offsets.front(), 0u);
  EXPECT_EQ(layout.chart_offsets.back(), layout.texels.size());
  std::vector<bool> textured(num_faces, false);
  std::set<std::tuple<int, int, int>> cells;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    std::size_t next = layout.chart_offsets[c];
    for (std::uint32_t face : charts[c].faces) {
      textured[face] = true;
      const auto [begin, end] = layout.face_ranges[face];
      if (overlapping_faces && begin == end) continue;
      EXPECT_EQ(begin, next) << "face " << face << " does not follow the previous face of chart " << c;
      EXPECT_LT(begin, end) << "face " << face << " has no texels";
      next = end;
      for (std::size_t t = begin; t < end; ++t) EXPECT_EQ(layout.texels[t].face, face);
    }
    EXPECT_EQ(next, layout.chart_offsets[c + 1]) << "chart " << c;
    const AtlasPlacement& placement = atlas.placements[c];
    for (std::size_t t = layout.chart_offsets[c]; t < layout.chart_offsets[c + 1]; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      EXPECT_EQ(texel.page, placement.page);
      EXPECT_GE(texel.x, placement.x);
      EXPECT_LT(texel.x, placement.x + charts[c].width);
      EXPECT_GE(texel.y, placement.y);
      EXPECT_LT(texel.y, placement.y + charts[c].height);
      EXPECT_TRUE(cells.insert({texel.page, texel.x, texel.y}).second)
          << "texel (" << texel.x << ", " << texel.y << ") of page " << texel.page << " twice";
    }
  }
  for (std::size_t f = 0; f < num_faces; ++f) {
    if (!textured[f]) {
      EXPECT_EQ(layout.face_ranges[f].first, layout.face_ranges[f].second) << "face " << f;
    }
  }
}

// `count` charts of 34 x 34 texels, each of `faces_per_chart` random triangles (some slivers); faces are
// numbered chart after chart.
std::vector<TextureChart> RandomCharts(unsigned seed, int count, int faces_per_chart) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(3.0f, 30.0f);
  std::vector<TextureChart> charts;
  std::uint32_t face = 0;
  for (int c = 0; c < count; ++c) {
    TextureChart chart;
    chart.width = chart.height = 34;
    for (int i = 0; i < faces_per_chart; ++i) {
      chart.faces.push_back(face++);
      for (int k = 0; k < 3; ++k) chart.corner_texels.emplace_back(coordinate(random), coordinate(random));
    }
    charts.push_back(chart);
  }
  return charts;
}

std::vector<cv::Size> Rectangles(const std::vector<TextureChart>& charts) {
  std::vector<cv::Size> rectangles;
  for (const TextureChart& chart : charts) rectangles.emplace_back(chart.width, chart.height);
  return rectangles;
}

TEST(RasterizeTexels, WithoutGutterEveryTexelInsideTheChartShowsThePointUnderItsCentre) {
  const std::vector<TextureChart> charts = {SquareChart(0, 1)};
  AtlasLayout atlas;
  atlas.placements = {{0, 7, 3}};
  atlas.page_sizes = {cv::Size(40, 30)};
  const TexelLayout layout = RasterizeTexels(charts, atlas, 2, 0.0, 1);
  ExpectConsistentLayout(layout, charts, atlas, 2);
  // Centres (i + 0.5, j + 0.5) inside [4, 20]^2: i, j in 4..19.
  ASSERT_EQ(layout.texels.size(), 16u * 16u);
  std::set<std::pair<int, int>> cells;
  for (const AtlasTexel& texel : layout.texels) {
    const int col = texel.x - 7, row = texel.y - 3;
    cells.insert({col, row});
    EXPECT_GE(col, 4);
    EXPECT_LE(col, 19);
    EXPECT_GE(row, 4);
    EXPECT_LE(row, 19);
    EXPECT_TRUE(OnTriangle(texel));
    const Eigen::Vector2d centre(col + 0.5, row + 0.5);
    EXPECT_LT((ChartPoint(charts[0], texel.face, texel) - centre).norm(), 1e-4) << col << ", " << row;
    // Off the diagonal a centre lies in exactly one of the triangles.
    if (col > row) {
      EXPECT_EQ(texel.face, 0u) << col << ", " << row;
    }
    if (col < row) {
      EXPECT_EQ(texel.face, 1u) << col << ", " << row;
    }
  }
  EXPECT_EQ(cells.size(), 16u * 16u);
}

TEST(RasterizeTexels, BorderTexelsWithinTheGutterShowTheNearestPointOfTheChart) {
  const std::vector<TextureChart> charts = {SquareChart(0, 1)};
  AtlasLayout atlas;
  atlas.placements = {{0, 0, 0}};
  atlas.page_sizes = {cv::Size(24, 24)};
  const double gutter = 2.0;
  const TexelLayout layout = RasterizeTexels(charts, atlas, 2, gutter, 1);
  ExpectConsistentLayout(layout, charts, atlas, 2);
  // Exactly the texels whose centre is within the gutter of the square.
  std::set<std::pair<int, int>> expected;
  for (int row = 0; row < 24; ++row) {
    for (int col = 0; col < 24; ++col) {
      if (DistanceToSquare({col + 0.5, row + 0.5}) <= gutter) expected.insert({col, row});
    }
  }
  EXPECT_EQ(expected.size(), 20u * 20u - 4u);  // the band of 2 texels, less the 4 farthest corner texels
  std::set<std::pair<int, int>> got;
  std::size_t border = 0;
  for (const AtlasTexel& texel : layout.texels) {
    got.insert({texel.x, texel.y});
    ASSERT_TRUE(OnTriangle(texel)) << texel.x << ", " << texel.y;
    const Eigen::Vector2d centre(texel.x + 0.5, texel.y + 0.5);
    // The square is convex: the nearest point of the nearest triangle is the nearest point of the chart.
    const Eigen::Vector2d nearest =
        centre.cwiseMax(Eigen::Vector2d::Constant(4.0)).cwiseMin(Eigen::Vector2d::Constant(20.0));
    EXPECT_LT((ChartPoint(charts[0], texel.face, texel) - nearest).norm(), 1e-4) << texel.x << ", " << texel.y;
    if (DistanceToSquare(centre) > 0.0) ++border;
  }
  EXPECT_EQ(got, expected);
  EXPECT_EQ(border, 20u * 20u - 4u - 16u * 16u);
}

TEST(RasterizeTexels, TexelsAreOrderedChartByChartAndFaceByFace) {
  // Two charts on two pages; faces 2 and 5 are in no chart. Chart faces are not in ascending order.
  std::vector<TextureChart> charts = {SquareChart(3, 1), SquareChart(4, 0)};
  AtlasLayout atlas;
  atlas.placements = {{1, 5, 0}, {0, 0, 24}};
  atlas.page_sizes = {cv::Size(24, 48), cv::Size(29, 24)};
  const TexelLayout layout = RasterizeTexels(charts, atlas, 6, 1.0, 1);
  ExpectConsistentLayout(layout, charts, atlas, 6);
  EXPECT_EQ(layout.face_ranges[2].first, layout.face_ranges[2].second);
  EXPECT_EQ(layout.face_ranges[5].first, layout.face_ranges[5].second);
  // The two charts are the same square: the same number of texels, the lower triangle's first.
  EXPECT_EQ(layout.chart_offsets[1] - layout.chart_offsets[0], layout.chart_offsets[2] - layout.chart_offsets[1]);
  EXPECT_EQ(layout.face_ranges[3].first, 0u);
  EXPECT_EQ(layout.face_ranges[1].first, layout.face_ranges[3].second);
  EXPECT_EQ(layout.face_ranges[4].first, layout.chart_offsets[1]);
  EXPECT_EQ(layout.face_ranges[0].first, layout.face_ranges[4].second);
  for (std::size_t c = 0; c < 2; ++c) {
    for (std::size_t t = layout.chart_offsets[c]; t < layout.chart_offsets[c + 1]; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      const Eigen::Vector2d centre(texel.x - atlas.placements[c].x + 0.5, texel.y - atlas.placements[c].y + 0.5);
      EXPECT_LE(DistanceToSquare(centre), 1.0);
      const Eigen::Vector2d nearest =
          centre.cwiseMax(Eigen::Vector2d::Constant(4.0)).cwiseMin(Eigen::Vector2d::Constant(20.0));
      EXPECT_LT((ChartPoint(charts[c], FaceIndexInChart(charts[c], texel.face), texel) - nearest).norm(), 1e-4);
    }
  }
}

TEST(RasterizeTexels, TheResultDoesNotDependOnTheThreadCount) {
  // Charts of random triangles (some slivers), packed into a few pages.
  const std::vector<TextureChart> charts = RandomCharts(7, 24, 3);
  const std::uint32_t face = 24 * 3;
  const AtlasLayout atlas = PackAtlas(Rectangles(charts), 128);
  const TexelLayout one = RasterizeTexels(charts, atlas, face, 2.0, 1);
  const TexelLayout several = RasterizeTexels(charts, atlas, face, 2.0, 3);
  ExpectConsistentLayout(one, charts, atlas, face, /*overlapping_faces=*/true);
  ASSERT_EQ(one.texels.size(), several.texels.size());
  EXPECT_EQ(one.face_ranges, several.face_ranges);
  EXPECT_EQ(one.chart_offsets, several.chart_offsets);
  for (std::size_t t = 0; t < one.texels.size(); ++t) {
    const AtlasTexel& a = one.texels[t];
    const AtlasTexel& b = several.texels[t];
    ASSERT_TRUE(a.face == b.face && a.page == b.page && a.x == b.x && a.y == b.y && a.b1 == b.b1 && a.b2 == b.b2)
        << "texel " << t;
  }
}

TEST(RasterizeTexels, ABatchOfChartsGetsTheTexelsTheWholeAtlasGivesThem) {
  const std::vector<TextureChart> charts = RandomCharts(11, 12, 2);
  const std::uint32_t face = 12 * 2;
  const AtlasLayout atlas = PackAtlas(Rectangles(charts), 128);
  const TexelLayout whole = RasterizeTexels(charts, atlas, face, 2.0, 2);
  const std::vector<std::size_t> counts = CountChartTexels(charts, 2.0, 2);
  ASSERT_EQ(counts.size(), charts.size());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    EXPECT_EQ(counts[c], whole.chart_offsets[c + 1] - whole.chart_offsets[c]) << "chart " << c;
  }
  // Charts 7, 2 and 9, in that order: each chart's texels are the whole atlas's, and the faces of the
  // other charts have none.
  const std::vector<std::size_t> batch = {7, 2, 9};
  const TexelLayout part = RasterizeTexels(charts, atlas, batch, face, 2.0, 2);
  ASSERT_EQ(part.chart_offsets.size(), batch.size() + 1);
  for (std::size_t i = 0; i < batch.size(); ++i) {
    const std::size_t c = batch[i];
    ASSERT_EQ(part.chart_offsets[i + 1] - part.chart_offsets[i], counts[c]);
    for (std::size_t k = 0; k < counts[c]; ++k) {
      const AtlasTexel& a = part.texels[part.chart_offsets[i] + k];
      const AtlasTexel& b = whole.texels[whole.chart_offsets[c] + k];
      ASSERT_TRUE(a.face == b.face && a.page == b.page && a.x == b.x && a.y == b.y && a.b1 == b.b1 && a.b2 == b.b2);
    }
  }
  for (std::uint32_t f = 0; f < face; ++f) {
    const bool in_batch = f / 2 == 7 || f / 2 == 2 || f / 2 == 9;
    const bool textured = whole.face_ranges[f].second > whole.face_ranges[f].first;
    EXPECT_EQ(part.face_ranges[f].second > part.face_ranges[f].first, in_batch && textured) << "face " << f;
  }
}

TEST(RasterizeTexels, TexelsOfAFloorChartMapToSurfacePointsThatProjectOntoTheirCentres) {
  const Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 1.0, 0.0, 0.6, 5, 3);
  const FaceAdjacency adjacency(mesh);
  // A camera looking straight down from 1 unit with focal 60: 60 texels per unit, 12 per cell.
  const std::vector<TextureView> views = {{"down", Camera::Pinhole(1, 100, 100, 60.0, 60.0),
                                           CamFromWorldLookingAt({0.5, 0.3, 1.0}, -Eigen::Vector3d::UnitZ(),
                                                                 Eigen::Vector3d::UnitY())}};
  // Two charts (left and right of x = 0.4), so the atlas places them apart.
  std::vector<std::uint32_t> view_of_face(mesh.faces.size(), 0u);
  std::vector<TextureView> two_views = {views[0], views[0]};
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const double x = (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]).x() / 3.0;
    view_of_face[f] = x < 0.4 ? 0u : 1u;
  }
  TextureChartOptions chart_options;
  chart_options.padding = 3;
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, two_views, view_of_face, chart_options);
  ASSERT_EQ(charts.size(), 2u);
  std::vector<cv::Size> rectangles;
  for (const TextureChart& chart : charts) rectangles.emplace_back(chart.width, chart.height);
  const AtlasLayout atlas = PackAtlas(rectangles, 256);
  const double gutter = 2.0;
  const TexelLayout layout = RasterizeTexels(charts, atlas, mesh.faces.size(), gutter, 2);
  ExpectConsistentLayout(layout, charts, atlas, mesh.faces.size());
  std::size_t interior = 0, border = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const TextureChart& chart = charts[c];
    const TextureView& view = two_views[chart.view];
    // Chart texels are the view's pixels shifted by one offset (the chart's and its placement's).
    const Eigen::Vector2d offset =
        chart.corner_texels[0].cast<double>() -
        view.camera.ImgFromCam(view.cam_from_world * mesh.vertices[mesh.faces[chart.faces[0]][0]]) +
        Eigen::Vector2d(atlas.placements[c].x, atlas.placements[c].y);
    std::set<std::pair<int, int>> present;
    for (std::size_t t = layout.chart_offsets[c]; t < layout.chart_offsets[c + 1]; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      present.insert({texel.x, texel.y});
      ASSERT_TRUE(OnTriangle(texel));
      const Mesh::Face& corners = mesh.faces[texel.face];
      const Eigen::Vector3d point = (1.0 - texel.b1 - texel.b2) * mesh.vertices[corners[0]] +
                                    double(texel.b1) * mesh.vertices[corners[1]] + double(texel.b2) * mesh.vertices[corners[2]];
      const Eigen::Vector2d projected = view.camera.ImgFromCam(view.cam_from_world * point) + offset;
      const Eigen::Vector2d centre(texel.x + 0.5, texel.y + 0.5);
      const double distance = (projected - centre).norm();
      EXPECT_LE(distance, gutter + 1e-3);
      // Centres inside the face's projection show exactly the point under them.
      const Eigen::Vector2d q = centre - Eigen::Vector2d(atlas.placements[c].x, atlas.placements[c].y);
      const std::size_t i = FaceIndexInChart(chart, texel.face);
      const Eigen::Vector2d p0 = chart.corner_texels[3 * i].cast<double>(), p1 = chart.corner_texels[3 * i + 1].cast<double>(),
                            p2 = chart.corner_texels[3 * i + 2].cast<double>();
      auto side = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
        return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
      };
      const double s0 = side(p0, p1, q), s1 = side(p1, p2, q), s2 = side(p2, p0, q);
      if ((s0 > 1e-3 && s1 > 1e-3 && s2 > 1e-3) || (s0 < -1e-3 && s1 < -1e-3 && s2 < -1e-3)) {
        EXPECT_LT(distance, 1e-3) << "texel (" << texel.x << ", " << texel.y << ")";
        ++interior;
      } else {
        ++border;
      }
    }
    // Every texel whose centre lies inside the chart's projection, and every one within the gutter of
    // it, is in the layout (the chart's texels cover it, borders included).
    const double x_low = chart.corner_texels[0].x(), y_low = chart.corner_texels[0].y();
    double x_min = x_low, x_max = x_low, y_min = y_low, y_max = y_low;
    for (const Eigen::Vector2f& corner : chart.corner_texels) {
      x_min = std::min(x_min, double(corner.x()));
      x_max = std::max(x_max, double(corner.x()));
      y_min = std::min(y_min, double(corner.y()));
      y_max = std::max(y_max, double(corner.y()));
    }
    // The chart is a rectangle of cells: its projection is the box [x_min, x_max] x [y_min, y_max].
    for (int row = 0; row < chart.height; ++row) {
      for (int col = 0; col < chart.width; ++col) {
        const Eigen::Vector2d q(col + 0.5, row + 0.5);
        const Eigen::Vector2d nearest = q.cwiseMax(Eigen::Vector2d(x_min, y_min)).cwiseMin(Eigen::Vector2d(x_max, y_max));
        const double d = (q - nearest).norm();
        const bool in_page = present.count({atlas.placements[c].x + col, atlas.placements[c].y + row}) > 0;
        if (d <= gutter - 1e-3) {
          EXPECT_TRUE(in_page) << "chart " << c << " texel " << col << ", " << row << " missing";
        }
        if (d > gutter + 1e-3) {
          EXPECT_FALSE(in_page) << "chart " << c << " texel " << col << ", " << row << " beyond the gutter";
        }
      }
    }
  }
  // 60 x 36 texels of surface in all: the interior texels account for them up to the diagonals and the
  // boundaries, which the strict inside test above leaves out.
  EXPECT_GT(static_cast<double>(interior), 0.8 * 60 * 36);
  EXPECT_LE(interior, 60u * 36u);
  EXPECT_GT(border, 0u);
}

}  // namespace
}  // namespace lutex
