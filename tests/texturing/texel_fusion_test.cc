// Fuses the texels of a flat floor from views whose images are known exactly: constant colours, a
// colour linear in the surface position, an outlier view, views at different distances and confidences,
// and a floating box that hides part of the floor from one view.

#include "texturing/texel_fusion.h"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/rendered_views.h"
#include "texturing/atlas_packing.h"
#include "texturing/face_adjacency.h"
#include "texturing/texture_charts.h"
#include "texturing/view_selection.h"

namespace lutex {
namespace {

const Eigen::Vector3f kGrey(0.3f, 0.5f, 0.7f);
const Eigen::Vector3f kWhite(1.0f, 1.0f, 1.0f);

// Floor z = 0 over [-0.7, 0.7]^2 in cells of 0.1. Only the faces inside [-0.5, 0.5]^2 are textured, so
// every textured point has floor around it in every view.
Mesh Floor() { return MakeHeightFieldMesh([](double, double) { return 0.0; }, -0.7, 0.7, -0.7, 0.7, 14, 14); }

bool IsTextured(const Mesh& mesh, std::uint32_t f) {
  for (std::uint32_t v : mesh.faces[f]) {
    if (std::abs(mesh.vertices[v].x()) > 0.5 + 1e-9 || std::abs(mesh.vertices[v].y()) > 0.5 + 1e-9) return false;
  }
  return mesh.vertices[mesh.faces[f][0]].z() == 0.0;
}

TextureView LookingAt(const Eigen::Vector3d& centre, const Eigen::Vector3d& target, int size = 160) {
  const Eigen::Vector3d forward = target - centre;
  const Eigen::Vector3d down = std::abs(forward.normalized().z()) > 0.99 ? Eigen::Vector3d(Eigen::Vector3d::UnitY())
                                                                         : Eigen::Vector3d(-Eigen::Vector3d::UnitZ());
  return {"view", Camera::Pinhole(static_cast<std::uint32_t>(size), static_cast<std::uint64_t>(size),
                                  static_cast<std::uint64_t>(size), 150.0, 150.0),
          CamFromWorldLookingAt(centre, forward, down)};
}

TextureView Above(double x, double y, double height) { return LookingAt({x, y, height}, {x, y, 0.0}); }

Shader Constant(const Eigen::Vector3f& colour) {
  return [colour](int, const Eigen::Vector3d&) { return colour; };
}

// A colour linear in the position on the floor, in [0.2, 0.7].
Eigen::Vector3f LinearAlbedo(const Eigen::Vector3d& p) {
  return {float(0.45 + 0.3 * p.x()), float(0.45 + 0.2 * p.y()), float(0.45 + 0.2 * p.x() - 0.2 * p.y())};
}

// The floor (and whatever else `mesh` has), the views and their images, every textured face a
// candidate of every view, and the texel layout of the charts of `chart_view_of_face`.
class FusionScene {
 public:
  FusionScene(Mesh mesh, std::vector<TextureView> views, const std::vector<Shader>& shaders)
      : mesh_(std::move(mesh)), scene_(mesh_), raycaster_(scene_), views_(std::move(views)),
        candidates_(mesh_.faces.size(), 8) {
    for (std::size_t v = 0; v < views_.size(); ++v) images_.push_back(RenderShaded(scene_, views_[v], shaders[v]));
    source_.linear_rgb = [this](std::size_t v, const cv::Rect& window) { return ViewWindow(images_[v], window); };
    for (std::uint32_t f = 0; f < mesh_.faces.size(); ++f) {
      if (!IsTextured(mesh_, f)) continue;
      for (std::uint32_t v = 0; v < views_.size(); ++v) candidates_.Offer(f, {v, 1.0f});
    }
  }

  // Charts of `view_of_face` (kNoView: untextured), packed and rasterised with a gutter of 1.5 texels.
  void Layout(const std::vector<std::uint32_t>& view_of_face) {
    const FaceAdjacency adjacency(mesh_);
    charts_ = BuildTextureCharts(mesh_, adjacency, views_, view_of_face, {});
    std::vector<cv::Size> rectangles;
    for (const TextureChart& chart : charts_) rectangles.emplace_back(chart.width, chart.height);
    atlas_ = PackAtlas(rectangles, 1024);
    layout_ = RasterizeTexels(charts_, atlas_, mesh_.faces.size(), 1.5, 2);
  }
  // Every textured face given `view`.
  std::vector<std::uint32_t> AllFaces(std::uint32_t view) const {
    std::vector<std::uint32_t> view_of_face(mesh_.faces.size(), kNoView);
    for (std::uint32_t f = 0; f < mesh_.faces.size(); ++f) {
      if (IsTextured(mesh_, f)) view_of_face[f] = view;
    }
    return view_of_face;
  }

  TexelFusionSummary Fuse(const std::vector<std::uint32_t>& view_of_face, const TexelFusionOptions& options,
                          std::vector<cv::Mat>& pages) const {
    pages.clear();
    for (const cv::Size& size : atlas_.page_sizes) pages.emplace_back(size, CV_32FC3, cv::Scalar::all(-1.0));
    return FuseTexels(mesh_, views_, raycaster_, source_, candidates_, view_of_face, layout_, options, pages);
  }

  Eigen::Vector3d Centroid(std::uint32_t f) const {
    return (mesh_.vertices[mesh_.faces[f][0]] + mesh_.vertices[mesh_.faces[f][1]] + mesh_.vertices[mesh_.faces[f][2]]) / 3.0;
  }

  Eigen::Vector3d SurfacePoint(const AtlasTexel& texel) const {
    const Mesh::Face& face = mesh_.faces[texel.face];
    return (1.0 - texel.b1 - texel.b2) * mesh_.vertices[face[0]] + double(texel.b1) * mesh_.vertices[face[1]] +
           double(texel.b2) * mesh_.vertices[face[2]];
  }

  // The weight the header documents for a sample of `view` at `point` of the floor (normal +z):
  // confidence x cos(viewing angle) x (focal / depth)^2.
  double Weight(std::size_t view, const Eigen::Vector3d& point, double confidence) const {
    const TextureView& v = views_[view];
    const Eigen::Vector3d centre = v.cam_from_world.Inverse() * Eigen::Vector3d::Zero();
    const double cos_angle = std::abs((centre - point).normalized().z());
    const double depth = (v.cam_from_world * point).z();
    const double focal = 0.5 * (v.camera.FocalLengthX() + v.camera.FocalLengthY());
    return confidence * cos_angle * (focal / depth) * (focal / depth);
  }

  Mesh mesh_;
  RaycastScene scene_;
  ViewRaycaster raycaster_;
  std::vector<TextureView> views_;
  std::vector<cv::Mat> images_;
  ViewImageSource source_;
  FaceViewCandidates candidates_;
  std::vector<TextureChart> charts_;
  AtlasLayout atlas_;
  TexelLayout layout_;
};

Eigen::Vector3f TexelColour(const std::vector<cv::Mat>& pages, const AtlasTexel& texel) {
  const cv::Vec3f& value = pages[texel.page].at<cv::Vec3f>(texel.y, texel.x);
  return {value[0], value[1], value[2]};
}

TEST(ParseTexelBlend, KnowsFuseAndSingle) {
  EXPECT_EQ(ParseTexelBlend("fuse"), TexelBlend::kFuse);
  EXPECT_EQ(ParseTexelBlend("single"), TexelBlend::kSingle);
  EXPECT_THROW(ParseTexelBlend("Fuse"), std::invalid_argument);
  EXPECT_THROW(ParseTexelBlend(""), std::invalid_argument);
  EXPECT_THROW(ParseTexelBlend("mean"), std::invalid_argument);
}

TEST(FuseTexels, ViewsThatAllShowOneColourGiveThatColour) {
  FusionScene scene(Floor(), {Above(0.0, 0.0, 1.5), Above(0.25, 0.0, 1.5), Above(-0.2, 0.2, 1.5), Above(0.1, -0.25, 1.6)},
                    {Constant(kGrey), Constant(kGrey), Constant(kGrey), Constant(kGrey)});
  const std::vector<std::uint32_t> view_of_face = scene.AllFaces(0);
  scene.Layout(view_of_face);
  ASSERT_GT(scene.layout_.texels.size(), 5000u);
  for (TexelBlend blend : {TexelBlend::kFuse, TexelBlend::kSingle}) {
    TexelFusionOptions options;
    options.blend = blend;
    std::vector<cv::Mat> pages;
    const TexelFusionSummary summary = scene.Fuse(view_of_face, options, pages);
    EXPECT_EQ(summary.num_texels, scene.layout_.texels.size());
    EXPECT_EQ(summary.num_passes, 1);
    EXPECT_EQ(summary.texels_without_samples, 0u);
    EXPECT_EQ(summary.rejected_samples, 0u);
    // Every view sees every textured point.
    EXPECT_DOUBLE_EQ(summary.mean_samples_per_texel, 4.0);
    for (const AtlasTexel& texel : scene.layout_.texels) {
      ASSERT_LT((TexelColour(pages, texel) - kGrey).cwiseAbs().maxCoeff(), 1e-5f) << texel.x << ", " << texel.y;
    }
  }
}

TEST(FuseTexels, TexelsShowTheColourOfTheirSurfacePoint) {
  const Shader albedo = [](int, const Eigen::Vector3d& p) { return LinearAlbedo(p); };
  FusionScene scene(Floor(), {Above(0.0, 0.0, 1.5), Above(0.2, 0.1, 1.4), Above(-0.15, -0.2, 1.7)}, {albedo, albedo, albedo});
  // Charts of all three views: the left third from view 1, the right third from view 2.
  std::vector<std::uint32_t> view_of_face = scene.AllFaces(0);
  for (std::uint32_t f = 0; f < view_of_face.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    const double x = scene.Centroid(f).x();
    view_of_face[f] = x < -0.2 ? 1u : x > 0.2 ? 2u : 0u;
  }
  scene.Layout(view_of_face);
  ASSERT_GE(scene.charts_.size(), 3u);
  for (TexelBlend blend : {TexelBlend::kFuse, TexelBlend::kSingle}) {
    TexelFusionOptions options;
    options.blend = blend;
    std::vector<cv::Mat> pages;
    const TexelFusionSummary summary = scene.Fuse(view_of_face, options, pages);
    EXPECT_EQ(summary.texels_without_samples, 0u);
    EXPECT_EQ(summary.rejected_samples, 0u);
    // Looking straight down on a plane, pixels are an affine map of the floor: bilinear sampling of a
    // linear colour is exact.
    for (const AtlasTexel& texel : scene.layout_.texels) {
      ASSERT_LT((TexelColour(pages, texel) - LinearAlbedo(scene.SurfacePoint(texel))).cwiseAbs().maxCoeff(), 1e-4f)
          << "texel (" << texel.x << ", " << texel.y << ") of face " << texel.face;
    }
  }
}

TEST(FuseTexels, AnOutlierViewIsRejected) {
  // Three views show the floor's grey; the fourth sees a highlight (white) everywhere.
  FusionScene scene(Floor(), {Above(0.0, 0.0, 1.5), Above(0.2, 0.0, 1.5), Above(-0.2, 0.1, 1.5), Above(0.0, 0.2, 1.5)},
                    {Constant(kGrey), Constant(kGrey), Constant(kGrey), Constant(kWhite)});
  std::vector<std::uint32_t> view_of_face = scene.AllFaces(3);
  scene.Layout(view_of_face);
  std::vector<cv::Mat> pages;
  // Even where the view selection chose the outlier view, the median of four rejects it.
  const TexelFusionSummary summary = scene.Fuse(view_of_face, {}, pages);
  EXPECT_EQ(summary.texels_without_samples, 0u);
  EXPECT_EQ(summary.rejected_samples, scene.layout_.texels.size());  // the outlier, at every texel
  for (const AtlasTexel& texel : scene.layout_.texels) {
    ASSERT_LT((TexelColour(pages, texel) - kGrey).cwiseAbs().maxCoeff(), 1e-5f) << texel.x << ", " << texel.y;
  }
  // kSingle keeps the chosen view, outlier or not.
  TexelFusionOptions single;
  single.blend = TexelBlend::kSingle;
  scene.Fuse(view_of_face, single, pages);
  for (const AtlasTexel& texel : scene.layout_.texels) {
    ASSERT_LT((TexelColour(pages, texel) - kWhite).cwiseAbs().maxCoeff(), 1e-5f) << texel.x << ", " << texel.y;
  }
  view_of_face = scene.AllFaces(1);
  scene.Fuse(view_of_face, single, pages);
  for (const AtlasTexel& texel : scene.layout_.texels) {
    ASSERT_LT((TexelColour(pages, texel) - kGrey).cwiseAbs().maxCoeff(), 1e-5f) << texel.x << ", " << texel.y;
  }
}

TEST(FuseTexels, WithTwoViewsOnlyAGrossDifferenceRejectsTheViewNotChosen) {
  const Eigen::Vector3f near_grey = kGrey + Eigen::Vector3f::Constant(0.05f);
  for (const bool gross : {true, false}) {
    const Eigen::Vector3f other = gross ? kWhite : near_grey;
    // View 0 at 1.5 units, view 1 at 2.5 units: view 0's samples weigh about (2.5 / 1.5)^2 times more.
    FusionScene scene(Floor(), {Above(0.05, 0.0, 1.5), Above(-0.1, 0.1, 2.5)}, {Constant(kGrey), Constant(other)});
    scene.Layout(scene.AllFaces(0));
    for (std::uint32_t chosen : {0u, 1u}) {
      std::vector<cv::Mat> pages;
      const TexelFusionSummary summary = scene.Fuse(scene.AllFaces(chosen), {}, pages);
      EXPECT_EQ(summary.texels_without_samples, 0u);
      EXPECT_DOUBLE_EQ(summary.mean_samples_per_texel, 2.0);
      EXPECT_EQ(summary.rejected_samples, gross ? scene.layout_.texels.size() : 0u);
      for (const AtlasTexel& texel : scene.layout_.texels) {
        Eigen::Vector3f expected;
        if (gross) {
          expected = chosen == 0 ? kGrey : kWhite;
        } else {
          // A mild difference: the weighted mean of the two.
          const Eigen::Vector3d point = scene.SurfacePoint(texel);
          const double w0 = scene.Weight(0, point, 1.0), w1 = scene.Weight(1, point, 1.0);
          expected = ((w0 * kGrey.cast<double>() + w1 * near_grey.cast<double>()) / (w0 + w1)).cast<float>();
        }
        ASSERT_LT((TexelColour(pages, texel) - expected).cwiseAbs().maxCoeff(), 1e-4f)
            << (gross ? "gross" : "mild") << ", chosen " << chosen << ", texel " << texel.x << ", " << texel.y;
      }
    }
  }
}

TEST(FuseTexels, ConfidenceScalesAViewsWeight) {
  const Eigen::Vector3f near_grey = kGrey + Eigen::Vector3f::Constant(0.05f);
  FusionScene scene(Floor(), {Above(0.0, 0.0, 1.5), Above(0.1, -0.1, 1.5)}, {Constant(kGrey), Constant(near_grey)});
  scene.Layout(scene.AllFaces(0));
  for (const float confidence : {0.25f, 0.0f}) {
    // View 0 has no confidence map (fully trusted); view 1 is trusted `confidence`.
    scene.source_.confidence = [confidence](std::size_t v, const cv::Rect& window) {
      return v == 0 ? cv::Mat() : ViewWindow(cv::Mat(160, 160, CV_32FC3, cv::Scalar::all(confidence)), window);
    };
    std::vector<cv::Mat> pages;
    const TexelFusionSummary summary = scene.Fuse(scene.AllFaces(0), {}, pages);
    EXPECT_EQ(summary.texels_without_samples, 0u);
    // A sample of zero weight is no sample.
    EXPECT_DOUBLE_EQ(summary.mean_samples_per_texel, confidence > 0.0f ? 2.0 : 1.0);
    for (const AtlasTexel& texel : scene.layout_.texels) {
      const Eigen::Vector3d point = scene.SurfacePoint(texel);
      const double w0 = scene.Weight(0, point, 1.0), w1 = scene.Weight(1, point, confidence);
      const Eigen::Vector3f expected = ((w0 * kGrey.cast<double>() + w1 * near_grey.cast<double>()) / (w0 + w1)).cast<float>();
      ASSERT_LT((TexelColour(pages, texel) - expected).cwiseAbs().maxCoeff(), 1e-4f)
          << "confidence " << confidence << ", texel " << texel.x << ", " << texel.y;
    }
  }
}

enum class Sight { kClear, kHidden, kUnsure };

// Whether `view` sees `point` of the floor, by rays from the point and from points 0.04 around it (a few
// pixels) towards the camera: kUnsure near the edge of an occluder's shadow.
Sight SightOf(const RaycastScene& scene, const TextureView& view, const Eigen::Vector3d& point) {
  const Eigen::Vector3d centre = view.cam_from_world.Inverse() * Eigen::Vector3d::Zero();
  int hidden = 0, total = 0;
  for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.04, 0), Eigen::Vector2d(-0.04, 0),
                                        Eigen::Vector2d(0, 0.04), Eigen::Vector2d(0, -0.04)}) {
    const Eigen::Vector3d from = point + Eigen::Vector3d(offset.x(), offset.y(), 1e-6);
    const Eigen::Vector3d direction = (centre - from).normalized();
    const RayHit hit = scene.Intersect(from + 1e-4 * direction, direction);
    hidden += hit.hit && hit.distance < (centre - from).norm() - 1e-3;
    ++total;
  }
  return hidden == 0 ? Sight::kClear : hidden == total ? Sight::kHidden : Sight::kUnsure;
}

TEST(FuseTexels, OccludedViewsGiveNothingAndOccludersNeverBleedIn) {
  // A box floats over the middle of the floor. View 0, straight above, sees its top (white) instead of
  // the floor under it; view 1, from the side, sees the floor (orange) under part of it.
  const Eigen::Vector3f orange(0.6f, 0.2f, 0.1f);
  Mesh mesh = Floor();
  const std::size_t floor_faces = mesh.faces.size();
  AppendMesh(MakeBoxMesh({-0.2, -0.2, 0.4}, {0.2, 0.2, 0.6}), &mesh);
  auto floor_or_white = [floor_faces](const Eigen::Vector3f& floor) -> Shader {
    return [floor, floor_faces](int face, const Eigen::Vector3d&) {
      return static_cast<std::size_t>(face) < floor_faces ? floor : kWhite;
    };
  };
  FusionScene scene(std::move(mesh), {Above(0.0, 0.0, 2.0), LookingAt({0.6, 0.0, 1.6}, {0.0, 0.0, 0.0}, 240)},
                    {floor_or_white(kGrey), floor_or_white(orange)});
  const std::vector<std::uint32_t> view_of_face = scene.AllFaces(0);
  scene.Layout(view_of_face);
  for (TexelBlend blend : {TexelBlend::kFuse, TexelBlend::kSingle}) {
    TexelFusionOptions options;
    options.blend = blend;
    std::vector<cv::Mat> pages;
    const TexelFusionSummary summary = scene.Fuse(view_of_face, options, pages);
    std::size_t nan = 0, both = 0, only_side = 0, neither = 0;
    for (const AtlasTexel& texel : scene.layout_.texels) {
      const Eigen::Vector3f colour = TexelColour(pages, texel);
      if (!colour.allFinite()) {
        ++nan;
      } else {
        // Whatever a view sees of the floor, never the box in front of it.
        EXPECT_TRUE((colour - kGrey).cwiseAbs().maxCoeff() < 1e-5f || (colour - orange).cwiseAbs().maxCoeff() < 1e-5f)
            << "texel " << texel.x << ", " << texel.y << ": " << colour.transpose();
      }
      const Eigen::Vector3d point = scene.SurfacePoint(texel);
      const Sight above = SightOf(scene.scene_, scene.views_[0], point);
      const Sight side = SightOf(scene.scene_, scene.views_[1], point);
      if (above == Sight::kUnsure || side == Sight::kUnsure) continue;
      Eigen::Vector3f expected = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
      if (above == Sight::kClear) {
        // Seen by both, grey and orange differ grossly: the chosen view (0) wins; seen by view 0 alone: grey.
        expected = kGrey;
        both += side == Sight::kClear;
      } else if (side == Sight::kClear) {
        expected = orange;  // hidden from the chosen view: the one view that sees it
        ++only_side;
      } else {
        ++neither;
      }
      if (expected.allFinite()) {
        EXPECT_LT((colour - expected).cwiseAbs().maxCoeff(), 1e-5f)
            << "texel " << texel.x << ", " << texel.y << " at " << point.transpose() << ": " << colour.transpose();
      } else {
        EXPECT_FALSE(colour.allFinite()) << "texel " << texel.x << ", " << texel.y << " at " << point.transpose();
      }
    }
    EXPECT_EQ(summary.texels_without_samples, nan);
    // The scene has texels of every kind.
    EXPECT_GT(both, 1000u);
    EXPECT_GT(only_side, 100u);
    EXPECT_GT(neither, 100u);
  }
}

// A few texels scattered over the views (as seam points are) are sampled through depths cast at their
// pixels alone, not through a rendered window: they get the colours the same texels get in the whole
// layout, occlusion by the box included.
TEST(FuseTexels, FewScatteredTexelsGetTheColoursTheyGetInTheWholeLayout) {
  const Eigen::Vector3f orange(0.6f, 0.2f, 0.1f);
  Mesh mesh = Floor();
  const std::size_t floor_faces = mesh.faces.size();
  AppendMesh(MakeBoxMesh({-0.2, -0.2, 0.4}, {0.2, 0.2, 0.6}), &mesh);
  const Shader floor_linear_box_white = [floor_faces](int face, const Eigen::Vector3d& p) {
    return static_cast<std::size_t>(face) < floor_faces ? LinearAlbedo(p) : kWhite;
  };
  const Shader floor_orange_box_white = [floor_faces, orange](int face, const Eigen::Vector3d&) {
    return static_cast<std::size_t>(face) < floor_faces ? orange : kWhite;
  };
  FusionScene scene(std::move(mesh), {Above(0.0, 0.0, 2.0), LookingAt({0.6, 0.0, 1.6}, {0.0, 0.0, 0.0}, 240)},
                    {floor_linear_box_white, floor_orange_box_white});
  const std::vector<std::uint32_t> view_of_face = scene.AllFaces(0);
  scene.Layout(view_of_face);
  std::vector<cv::Mat> whole_pages;
  const TexelFusionSummary whole = scene.Fuse(view_of_face, {}, whole_pages);

  // The middle texel of every third face, one chart.
  TexelLayout scattered;
  scattered.face_ranges.assign(scene.mesh_.faces.size(), {0, 0});
  for (std::uint32_t f = 0; f < scene.mesh_.faces.size(); f += 3) {
    const auto [begin, end] = scene.layout_.face_ranges[f];
    if (begin == end) continue;
    scattered.face_ranges[f] = {scattered.texels.size(), scattered.texels.size() + 1};
    scattered.texels.push_back(scene.layout_.texels[(begin + end) / 2]);
  }
  scattered.chart_offsets = {0, scattered.texels.size()};
  ASSERT_GT(scattered.texels.size(), 50u);
  ASSERT_LT(scattered.texels.size(), 100u);
  std::vector<cv::Mat> scattered_pages;
  for (const cv::Mat& page : whole_pages) scattered_pages.emplace_back(page.size(), CV_32FC3, cv::Scalar::all(-1.0));
  const TexelFusionSummary few = FuseTexels(scene.mesh_, scene.views_, scene.raycaster_, scene.source_,
                                            scene.candidates_, view_of_face, scattered, {}, scattered_pages);
  EXPECT_EQ(whole.views_cast_by_pixel, 0u);
  EXPECT_EQ(few.views_cast_by_pixel, 2u);
  std::size_t hidden_from_above = 0;
  for (const AtlasTexel& texel : scattered.texels) {
    const Eigen::Vector3f expected = TexelColour(whole_pages, texel), colour = TexelColour(scattered_pages, texel);
    if (!expected.allFinite()) {
      EXPECT_FALSE(colour.allFinite());
      continue;
    }
    EXPECT_LT((colour - expected).cwiseAbs().maxCoeff(), 1e-6f) << "texel " << texel.x << ", " << texel.y;
    hidden_from_above += (colour - orange).cwiseAbs().maxCoeff() < 1e-5f;
  }
  EXPECT_GT(hidden_from_above, 0u);  // some of them only the side view sees
}

TEST(FuseTexels, PassesUnderATightMemoryLimitGiveTheSameTexture) {
  const Shader albedo = [](int, const Eigen::Vector3d& p) { return LinearAlbedo(p); };
  FusionScene scene(Floor(), {Above(0.0, 0.0, 1.5), Above(0.2, 0.2, 1.5), Above(-0.2, 0.2, 1.5), Above(0.0, -0.2, 1.5)},
                    {albedo, albedo, albedo, albedo});
  // Four charts, one per quadrant.
  std::vector<std::uint32_t> view_of_face = scene.AllFaces(0);
  for (std::uint32_t f = 0; f < view_of_face.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    const Eigen::Vector3d p = scene.Centroid(f);
    view_of_face[f] = (p.x() < 0.0 ? 0u : 1u) + (p.y() < 0.0 ? 0u : 2u);
  }
  scene.Layout(view_of_face);
  ASSERT_EQ(scene.charts_.size(), 4u);
  std::vector<cv::Mat> one_pass, many_passes;
  const TexelFusionSummary one = scene.Fuse(view_of_face, {}, one_pass);
  TexelFusionOptions tight;
  tight.memory_limit_bytes = 1;  // smaller than any chart: one pass per chart
  const TexelFusionSummary many = scene.Fuse(view_of_face, tight, many_passes);
  EXPECT_EQ(one.num_passes, 1);
  EXPECT_EQ(many.num_passes, 4);
  EXPECT_EQ(many.texels_without_samples, one.texels_without_samples);
  EXPECT_EQ(many.rejected_samples, one.rejected_samples);
  EXPECT_DOUBLE_EQ(many.mean_samples_per_texel, one.mean_samples_per_texel);
  ASSERT_EQ(one_pass.size(), many_passes.size());
  for (std::size_t p = 0; p < one_pass.size(); ++p) {
    EXPECT_EQ(cv::norm(one_pass[p], many_passes[p], cv::NORM_INF), 0.0) << "page " << p;
  }
  for (const AtlasTexel& texel : scene.layout_.texels) {
    ASSERT_LT((TexelColour(many_passes, texel) - LinearAlbedo(scene.SurfacePoint(texel))).cwiseAbs().maxCoeff(), 1e-4f);
  }
}

}  // namespace
}  // namespace lutex
