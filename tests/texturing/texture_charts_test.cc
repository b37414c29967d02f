// Charts of small synthetic meshes. Cameras look straight down on a flat floor, where the projection is
// a uniform scale of focal / height texels per scene unit: the charts' texel geometry is known exactly.

#include "texturing/texture_charts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "texturing/face_adjacency.h"
#include "texturing/view_selection.h"

namespace lutex {
namespace {

// A camera at `centre` looking straight down (-z), image "down" along +y.
TextureView DownView(std::uint32_t camera_id, const Eigen::Vector3d& centre, double focal) {
  return {"view_" + std::to_string(camera_id), Camera::Pinhole(camera_id, 400, 400, focal, focal),
          CamFromWorldLookingAt(centre, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY())};
}

// z = 0 over [0, 2] x [0, 1], cells of `cell` (two triangles each).
Mesh Floor(double cell) {
  return MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 2.0, 0.0, 1.0, static_cast<int>(std::lround(2.0 / cell)),
                             static_cast<int>(std::lround(1.0 / cell)));
}

Eigen::Vector3d Centroid(const Mesh& mesh, std::uint32_t f) {
  return (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]) / 3.0;
}

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Every labelled face in exactly one chart of its own view, unlabelled faces in none; faces ascending,
// one corner triple per face; unless `tiled`, charts in order of their smallest face (the tiles of one
// component come out together, in the order of their position in the view).
void ExpectPartitionOfLabelledFaces(const Mesh& mesh, const std::vector<std::uint32_t>& view_of_face,
                                    const std::vector<TextureChart>& charts, bool tiled = false) {
  std::vector<int> count(mesh.faces.size(), 0);
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const TextureChart& chart = charts[c];
    ASSERT_FALSE(chart.faces.empty()) << "chart " << c;
    ASSERT_EQ(chart.corner_texels.size(), 3 * chart.faces.size()) << "chart " << c;
    EXPECT_TRUE(std::is_sorted(chart.faces.begin(), chart.faces.end())) << "chart " << c;
    if (c > 0 && !tiled) {
      EXPECT_LT(charts[c - 1].faces.front(), chart.faces.front()) << "charts out of order at " << c;
    }
    for (std::uint32_t f : chart.faces) {
      ASSERT_LT(f, mesh.faces.size());
      ++count[f];
      EXPECT_EQ(view_of_face[f], chart.view) << "face " << f << " in a chart of another view";
    }
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    EXPECT_EQ(count[f], view_of_face[f] == kNoView ? 0 : 1) << "face " << f;
  }
}

// The chart's faces are connected through shared edges.
bool IsConnected(const TextureChart& chart, const FaceAdjacency& adjacency) {
  const std::set<std::uint32_t> members(chart.faces.begin(), chart.faces.end());
  std::set<std::uint32_t> reached{chart.faces.front()};
  std::vector<std::uint32_t> stack{chart.faces.front()};
  while (!stack.empty()) {
    const std::uint32_t f = stack.back();
    stack.pop_back();
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      if (members.count(*n) && reached.insert(*n).second) stack.push_back(*n);
    }
  }
  return reached.size() == members.size();
}

// Every corner inside the chart's rectangle less its padding, and the corners' bounding box touching
// the padding on every side (to within the rounding of the box to whole texels).
void ExpectCornersFillTheRectangle(const TextureChart& chart, int padding) {
  float x_low = std::numeric_limits<float>::infinity(), y_low = x_low, x_high = -x_low, y_high = -x_low;
  for (const Eigen::Vector2f& c : chart.corner_texels) {
    x_low = std::min(x_low, c.x());
    y_low = std::min(y_low, c.y());
    x_high = std::max(x_high, c.x());
    y_high = std::max(y_high, c.y());
  }
  const float p = static_cast<float>(padding);
  EXPECT_GE(x_low, p - 1e-3f);
  EXPECT_LT(x_low, p + 1.0f);
  EXPECT_GE(y_low, p - 1e-3f);
  EXPECT_LT(y_low, p + 1.0f);
  EXPECT_LE(x_high, static_cast<float>(chart.width) - p + 1e-3f);
  EXPECT_GT(x_high, static_cast<float>(chart.width) - p - 1.0f);
  EXPECT_LE(y_high, static_cast<float>(chart.height) - p + 1e-3f);
  EXPECT_GT(y_high, static_cast<float>(chart.height) - p - 1.0f);
}

// On the flat floor each corner-to-corner distance in texels is `texels_per_unit` x the distance on the
// surface, and every face keeps its orientation with `texels_per_unit`^2 x its area.
void ExpectUniformScale(const Mesh& mesh, const TextureChart& chart, double texels_per_unit) {
  double orientation = 0.0;
  for (std::size_t i = 0; i < chart.faces.size(); ++i) {
    const Mesh::Face& face = mesh.faces[chart.faces[i]];
    Eigen::Vector2d t[3];
    Eigen::Vector2d w[3];
    for (int k = 0; k < 3; ++k) {
      t[k] = chart.corner_texels[3 * i + k].cast<double>();
      w[k] = mesh.vertices[face[k]].head<2>();
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR((t[(k + 1) % 3] - t[k]).norm(), texels_per_unit * (w[(k + 1) % 3] - w[k]).norm(), 2e-3)
          << "face " << chart.faces[i] << " edge " << k;
    }
    const double area = Cross2(t[1] - t[0], t[2] - t[0]);
    const double world_area = std::abs(Cross2(w[1] - w[0], w[2] - w[0]));
    EXPECT_NEAR(std::abs(area), texels_per_unit * texels_per_unit * world_area, 1e-2 * texels_per_unit * texels_per_unit * world_area);
    if (orientation == 0.0) orientation = area;
    EXPECT_GT(area * orientation, 0.0) << "face " << chart.faces[i] << " folded over";
  }
}

TEST(TextureCharts, ChartsAreTheConnectedComponentsOfOneView) {
  const Mesh mesh = Floor(0.25);  // 8 x 4 cells, 64 faces
  const FaceAdjacency adjacency(mesh);
  const std::vector<TextureView> views = {DownView(1, {0.5, 0.5, 1.0}, 100.0), DownView(1, {1.5, 0.5, 1.0}, 100.0)};
  // Left (x < 0.75): view 0. A column of unlabelled faces (0.75 < x < 1.25). Right: view 1, except its
  // bottom row (y < 0.25), which is view 0 again but not connected to the left region.
  enum Region { kLeft, kIsland, kRight, kNone };
  std::vector<std::uint32_t> view_of_face(mesh.faces.size());
  std::vector<Region> region(mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d c = Centroid(mesh, f);
    region[f] = c.x() < 0.75 ? kLeft : c.x() < 1.25 ? kNone : c.y() < 0.25 ? kIsland : kRight;
    view_of_face[f] = region[f] == kLeft || region[f] == kIsland ? 0u : region[f] == kRight ? 1u : kNoView;
  }
  TextureChartOptions options;
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, options);
  ExpectPartitionOfLabelledFaces(mesh, view_of_face, charts);
  ASSERT_EQ(charts.size(), 3u);
  std::set<Region> seen;
  for (const TextureChart& chart : charts) {
    EXPECT_TRUE(IsConnected(chart, adjacency));
    const Region r = region[chart.faces.front()];
    for (std::uint32_t f : chart.faces) EXPECT_EQ(region[f], r) << "a chart mixes regions";
    seen.insert(r);
    ExpectCornersFillTheRectangle(chart, options.padding);
  }
  EXPECT_EQ(seen, (std::set<Region>{kLeft, kIsland, kRight}));
  // Components are maximal: no two charts of one view share an edge.
  std::vector<int> chart_of_face(mesh.faces.size(), -1);
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (std::uint32_t f : charts[c].faces) chart_of_face[f] = static_cast<int>(c);
  }
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      if (view_of_face[f] != kNoView && view_of_face[f] == view_of_face[*n]) {
        EXPECT_EQ(chart_of_face[f], chart_of_face[*n]);
      }
    }
  }
}

TEST(TextureCharts, FacesWithoutAViewAreInNoChart) {
  const Mesh mesh = Floor(0.25);
  const FaceAdjacency adjacency(mesh);
  const std::vector<TextureView> views = {DownView(1, {1.0, 0.5, 1.0}, 100.0)};
  EXPECT_TRUE(BuildTextureCharts(mesh, adjacency, views, std::vector<std::uint32_t>(mesh.faces.size(), kNoView), {}).empty());
  // A checkerboard of labelled and unlabelled cells: no two labelled faces of different cells share an
  // edge (cells touch only at corners), so each labelled cell is a chart of its two triangles.
  std::vector<std::uint32_t> view_of_face(mesh.faces.size(), kNoView);
  std::size_t labelled_cells = 0;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d c = Centroid(mesh, f);
    const int i = static_cast<int>(std::floor(c.x() / 0.25)), j = static_cast<int>(std::floor(c.y() / 0.25));
    if ((i + j) % 2 == 0) view_of_face[f] = 0;
  }
  labelled_cells = static_cast<std::size_t>(std::count(view_of_face.begin(), view_of_face.end(), 0u)) / 2;
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, {});
  ExpectPartitionOfLabelledFaces(mesh, view_of_face, charts);
  EXPECT_EQ(labelled_cells, 16u);
  ASSERT_EQ(charts.size(), labelled_cells);
  for (const TextureChart& chart : charts) {
    EXPECT_EQ(chart.faces.size(), 2u);
    EXPECT_TRUE(IsConnected(chart, adjacency));
  }
}

TEST(TextureCharts, NativeResolutionKeepsThePixelGridOfTheView) {
  const Mesh mesh = Floor(0.25);
  const FaceAdjacency adjacency(mesh);
  const double focal = 100.0, height = 2.0;  // 50 pixels per scene unit on the floor
  const std::vector<TextureView> views = {DownView(1, {1.0, 0.5, height}, focal)};
  TextureChartOptions options;
  options.padding = 3;
  const std::vector<TextureChart> charts =
      BuildTextureCharts(mesh, adjacency, views, std::vector<std::uint32_t>(mesh.faces.size(), 0u), options);
  ASSERT_EQ(charts.size(), 1u);
  const TextureChart& chart = charts[0];
  ExpectPartitionOfLabelledFaces(mesh, std::vector<std::uint32_t>(mesh.faces.size(), 0u), charts);
  ExpectUniformScale(mesh, chart, focal / height);
  ExpectCornersFillTheRectangle(chart, options.padding);
  // The floor is 2 x 1 units: 100 x 50 texels plus the padding (and at most one texel of rounding).
  EXPECT_GE(chart.width, 100 + 2 * options.padding);
  EXPECT_LE(chart.width, 101 + 2 * options.padding);
  EXPECT_GE(chart.height, 50 + 2 * options.padding);
  EXPECT_LE(chart.height, 51 + 2 * options.padding);
  // A texel is a pixel of the view: every corner is its vertex's pixel, shifted by one offset.
  const Eigen::Vector2d offset =
      chart.corner_texels[0].cast<double>() -
      views[0].camera.ImgFromCam(views[0].cam_from_world * mesh.vertices[mesh.faces[chart.faces[0]][0]]);
  for (std::size_t i = 0; i < chart.faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d pixel =
          views[0].camera.ImgFromCam(views[0].cam_from_world * mesh.vertices[mesh.faces[chart.faces[i]][k]]);
      EXPECT_LT((chart.corner_texels[3 * i + k].cast<double>() - pixel - offset).norm(), 1e-3);
    }
  }
}

TEST(TextureCharts, ProjectionOfACurvedSurfaceIsTheViewsImageShiftedAndNeverFolds) {
  const Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.1 * std::sin(3.0 * x) * std::cos(2.0 * y); },
                                        -1.0, 1.0, -1.0, 1.0, 12, 12);
  const FaceAdjacency adjacency(mesh);
  // An oblique view from the side, looking down at 45 degrees onto the middle of the surface.
  const Eigen::Vector3d centre(-2.0, 0.3, 2.0);
  const std::vector<TextureView> views = {{"oblique", Camera::Pinhole(1, 640, 480, 300.0, 300.0),
                                           CamFromWorldLookingAt(centre, -centre, Eigen::Vector3d::UnitX())}};
  const std::vector<std::uint32_t> view_of_face(mesh.faces.size(), 0u);
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, {});
  ASSERT_EQ(charts.size(), 1u);
  ExpectPartitionOfLabelledFaces(mesh, view_of_face, charts);
  const TextureChart& chart = charts[0];
  ExpectCornersFillTheRectangle(chart, TextureChartOptions().padding);
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double orientation = 0.0;
  for (std::size_t i = 0; i < chart.faces.size(); ++i) {
    Eigen::Vector2d pixel[3];
    for (int k = 0; k < 3; ++k) {
      pixel[k] = views[0].camera.ImgFromCam(views[0].cam_from_world * mesh.vertices[mesh.faces[chart.faces[i]][k]]);
      if (i == 0 && k == 0) offset = chart.corner_texels[0].cast<double>() - pixel[0];
      EXPECT_LT((chart.corner_texels[3 * i + k].cast<double>() - pixel[k] - offset).norm(), 1e-2);
    }
    // The surface faces the camera everywhere, so its projection keeps one orientation.
    const double area = Cross2(pixel[1] - pixel[0], pixel[2] - pixel[0]);
    const double chart_area = Cross2((chart.corner_texels[3 * i + 1] - chart.corner_texels[3 * i]).cast<double>(),
                                     (chart.corner_texels[3 * i + 2] - chart.corner_texels[3 * i]).cast<double>());
    EXPECT_NEAR(chart_area, area, 1e-2 * std::abs(area) + 1e-3);
    if (orientation == 0.0) orientation = chart_area;
    EXPECT_GT(chart_area * orientation, 0.0) << "face " << chart.faces[i] << " folded over";
  }
}

TEST(TextureCharts, TexelSizeSetsTheScaleWhateverTheViewDistance) {
  const Mesh mesh = Floor(0.25);
  const FaceAdjacency adjacency(mesh);
  // The left half seen from 1 unit, the right half from 3 units: 100 and 33 pixels per unit natively.
  const std::vector<TextureView> views = {DownView(1, {0.5, 0.5, 1.0}, 100.0), DownView(1, {1.5, 0.5, 3.0}, 100.0)};
  std::vector<std::uint32_t> view_of_face(mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) view_of_face[f] = Centroid(mesh, f).x() < 1.0 ? 0u : 1u;
  TextureChartOptions options;
  options.texel_size = 0.005;  // 200 texels per unit in both charts
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, options);
  ASSERT_EQ(charts.size(), 2u);
  ExpectPartitionOfLabelledFaces(mesh, view_of_face, charts);
  for (const TextureChart& chart : charts) {
    ExpectUniformScale(mesh, chart, 1.0 / options.texel_size);
    ExpectCornersFillTheRectangle(chart, options.padding);
    // Each half is 1 x 1 unit: 200 x 200 texels and the padding.
    EXPECT_NEAR(chart.width, 200 + 2 * options.padding, 1);
    EXPECT_NEAR(chart.height, 200 + 2 * options.padding, 1);
  }
  // Natively the two charts' scales differ by the ratio of the distances.
  const std::vector<TextureChart> native = BuildTextureCharts(mesh, adjacency, views, view_of_face, {});
  ASSERT_EQ(native.size(), 2u);
  for (const TextureChart& chart : native) ExpectUniformScale(mesh, chart, chart.view == 0 ? 100.0 : 100.0 / 3.0);
}

TEST(TextureCharts, AChartLargerThanAPageIsCutIntoTilesThatFit) {
  const Mesh mesh = Floor(0.125);  // 16 x 8 cells
  const FaceAdjacency adjacency(mesh);
  const std::vector<TextureView> views = {DownView(1, {1.0, 0.5, 1.0}, 200.0)};  // 400 x 200 texels
  const std::vector<std::uint32_t> view_of_face(mesh.faces.size(), 0u);
  TextureChartOptions options;
  options.padding = 4;
  options.max_size = 96;
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, options);
  ExpectPartitionOfLabelledFaces(mesh, view_of_face, charts, /*tiled=*/true);
  // A tile holds at most (96 - 2 x 4)^2 texels of surface: 400 x 200 need at least 11 of them.
  EXPECT_GE(charts.size(), 11u);
  for (const TextureChart& chart : charts) {
    EXPECT_EQ(chart.view, 0u);
    EXPECT_LE(chart.width, options.max_size);
    EXPECT_LE(chart.height, options.max_size);
    ExpectUniformScale(mesh, chart, 200.0);  // tiling moves faces, it does not rescale them
    ExpectCornersFillTheRectangle(chart, options.padding);
  }
  // Without the page limit it is one chart.
  options.max_size = 8192;
  EXPECT_EQ(BuildTextureCharts(mesh, adjacency, views, view_of_face, options).size(), 1u);
}

TEST(TextureChartOptions, RejectsInvalidOptions) {
  EXPECT_NO_THROW(TextureChartOptions().Check());
  auto with = [](auto change) {
    TextureChartOptions options;
    change(options);
    return options;
  };
  EXPECT_THROW(with([](TextureChartOptions& o) { o.texel_size = -0.001; }).Check(), std::invalid_argument);
  EXPECT_THROW(with([](TextureChartOptions& o) { o.texel_size = std::numeric_limits<double>::quiet_NaN(); }).Check(),
               std::invalid_argument);
  EXPECT_THROW(with([](TextureChartOptions& o) { o.texel_size = std::numeric_limits<double>::infinity(); }).Check(),
               std::invalid_argument);
  EXPECT_THROW(with([](TextureChartOptions& o) { o.padding = -1; }).Check(), std::invalid_argument);
  EXPECT_THROW(with([](TextureChartOptions& o) { o.padding = 65; }).Check(), std::invalid_argument);
  EXPECT_THROW(with([](TextureChartOptions& o) { o.max_size = 63; o.padding = 0; }).Check(), std::invalid_argument);
  EXPECT_NO_THROW(with([](TextureChartOptions& o) { o.max_size = 64; o.padding = 0; }).Check());
  // BuildTextureCharts checks its options.
  const Mesh mesh = Floor(0.5);
  const FaceAdjacency adjacency(mesh);
  const std::vector<TextureView> views = {DownView(1, {1.0, 0.5, 1.0}, 100.0)};
  EXPECT_THROW(BuildTextureCharts(mesh, adjacency, views, std::vector<std::uint32_t>(mesh.faces.size(), 0u),
                                  with([](TextureChartOptions& o) { o.padding = -1; })),
               std::invalid_argument);
}

}  // namespace
}  // namespace lutex
