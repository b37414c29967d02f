// Bakes a texture of a synthetic scene with a known albedo (a patchwork of colours on a gently curved
// floor) from views that show exactly that albedo, and checks the texture against it: rendered back
// through each camera, and at an outlier ("particle") one view adds.

#include "texturing/texture_baker.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/rendered_views.h"
#include "texturing/texture_transfer.h"

namespace lutex {
namespace {

struct Scene {
  Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.08 * std::sin(2.0 * x) * std::cos(1.5 * y); },
                                  -1.0, 1.0, -1.0, 1.0, 50, 50);
  std::vector<TextureView> views;
  Scene() {
    const Camera camera = Camera::Pinhole(1, 200, 150, 150.0, 150.0);
    int index = 0;
    for (double y : {-0.5, 0.0, 0.5}) {
      for (double x : {-0.5, 0.0, 0.5}) {
        const Eigen::Vector3d centre(x, y, 1.2);
        views.push_back({"view_" + std::to_string(index++), camera,
                         CamFromWorldLookingAt(centre, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY())});
      }
    }
  }
};

struct RenderBackError {
  double mean = 0.0;          // over all textured pixels and channels
  double median = 0.0;
  double mean_in_disc = 0.0;  // within `disc_radius` pixels of `disc_centre`
};

// The texture seen through `view` (ray cast + texture lookup) against the true albedo.
RenderBackError CompareThroughView(const RaycastScene& raycaster, const TextureView& view,
                                   const TexturedMesh& textured, const Eigen::Vector2d& disc_centre,
                                   double disc_radius) {
  const CameraRays rays(view.camera, 1);
  GeometryMapsOptions options;
  options.barycentrics = true;
  options.num_threads = 1;
  const GeometryMaps maps = raycaster.Render(rays, view.cam_from_world, options);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  std::vector<double> errors;
  double disc_sum = 0.0;
  int disc_count = 0;
  for (int row = 0; row < maps.depth.rows; ++row) {
    for (int col = 0; col < maps.depth.cols; ++col) {
      const int face = maps.face_id.at<int>(row, col);
      if (face < 0 || textured.face_page[face] < 0) continue;
      const cv::Vec2f b = maps.barycentrics.at<cv::Vec2f>(row, col);
      const Eigen::Vector3d point_in_cam = rays.Direction(col, row).cast<double>() / rays.Direction(col, row).z() *
                                           double(maps.depth.at<float>(row, col));
      const double error =
          (textured.AlbedoAt(face, b[0], b[1]) - PatchworkAlbedo(world_from_cam * point_in_cam)).cwiseAbs().mean();
      errors.push_back(error);
      if (std::hypot(col + 0.5 - disc_centre.x(), row + 0.5 - disc_centre.y()) < disc_radius) {
        disc_sum += error;
        ++disc_count;
      }
    }
  }
  RenderBackError result;
  for (double e : errors) result.mean += e / double(errors.size());
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  result.median = errors[errors.size() / 2];
  result.mean_in_disc = disc_count ? disc_sum / disc_count : 0.0;
  return result;
}

class TextureBakerTest : public ::testing::Test {
 protected:
  TextureBakerTest() : raycaster_(scene_.mesh) {
    for (const TextureView& view : scene_.views) images_.push_back(RenderPatchwork(raycaster_, view));
    source_.linear_rgb = [this](std::size_t v, const cv::Rect& window) { return ViewWindow(images_[v], window); };
  }
  Scene scene_;
  RaycastScene raycaster_;
  std::vector<cv::Mat> images_;
  ViewImageSource source_;
};

TEST_F(TextureBakerTest, RenderedBackTheTextureShowsTheTrueAlbedo) {
  TextureBakingOptions options;
  const TextureBakingResult result = BakeTexture(scene_.mesh, scene_.views, source_, options);
  // The views cover the middle of the floor; its edges (|x| or |y| > ~1) are outside every frustum.
  EXPECT_GT(result.summary.num_textured_faces, 0.6 * double(scene_.mesh.faces.size()));
  EXPECT_EQ(result.summary.num_pages, 1u);
  for (std::size_t v = 0; v < scene_.views.size(); v += 4) {
    const RenderBackError error =
        CompareThroughView(raycaster_, scene_.views[v], result.textured, Eigen::Vector2d::Zero(), 0.0);
    // Inside patches the texture is exact up to resampling; the patch borders blur over about a texel.
    EXPECT_LT(error.median, 0.002) << scene_.views[v].name;
    EXPECT_LT(error.mean, 0.02) << scene_.views[v].name;
  }
  // Where charts meet the texture has no seam: the colour step across chart borders is no larger than
  // across edges inside charts (the patchwork's own edges).
  EXPECT_GT(result.summary.seams.num_seam_edges, 0u);
  EXPECT_LT(result.summary.seams.Excess(), 0.002);
}

TEST_F(TextureBakerTest, FusionRejectsAParticleThatOneViewSees) {
  // The view that textures the middle of the floor (without confidence maps the choice does not depend
  // on the pixels) gets a bright disc there: a particle lit by the lights, or a specular highlight.
  TextureBakingOptions options;
  const TextureBakingResult clean = BakeTexture(scene_.mesh, scene_.views, source_, options);
  const RayHit hit = raycaster_.Intersect(Eigen::Vector3d(0.02, 0.03, 2.0), -Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(hit.hit);
  const std::uint32_t chosen = clean.view_of_face[hit.face_id];
  ASSERT_LT(chosen, scene_.views.size());
  const TextureView& view = scene_.views[chosen];
  const Eigen::Vector2d particle = view.camera.ImgFromCam(view.cam_from_world * Eigen::Vector3d(0.02, 0.03, 2.0 - hit.distance));
  cv::circle(images_[chosen], cv::Point(int(particle.x()), int(particle.y())), 12, cv::Scalar::all(1.0), cv::FILLED);

  const TextureBakingResult fused = BakeTexture(scene_.mesh, scene_.views, source_, options);
  options.fusion.blend = TexelBlend::kSingle;
  const TextureBakingResult single = BakeTexture(scene_.mesh, scene_.views, source_, options);
  const auto error_near_particle = [&](const TexturedMesh& textured) {
    return CompareThroughView(raycaster_, view, textured, particle, 10.0).mean_in_disc;
  };
  // One view per face shows the disc (errors of tens of percent); the fusion rejects it: the other
  // views that see the spot agree with each other.
  EXPECT_GT(error_near_particle(single.textured), 0.2);
  EXPECT_LT(error_near_particle(fused.textured), 0.02);
  EXPECT_LT(error_near_particle(clean.textured), 0.02);
  EXPECT_GT(fused.summary.fusion.rejected_samples, clean.summary.fusion.rejected_samples);
}

TEST_F(TextureBakerTest, SeamLevellingRemovesTheStepsBetweenViewsThatDisagree) {
  // Each view a few percent too bright or too dark (restored images of a dive disagree like this: strobe
  // power, a LUT's error that depends on range): with one view per face, every chart border between two
  // views is a step.
  for (std::size_t v = 0; v < images_.size(); ++v) images_[v] *= 1.0 + 0.12 * std::sin(2.0 * double(v) + 0.5);
  const auto bake = [&](TexelBlend blend, bool level) {
    TextureBakingOptions options;
    options.fusion.blend = blend;
    options.levelling.enabled = level;
    return BakeTexture(scene_.mesh, scene_.views, source_, options);
  };
  const auto error = [&](const TextureBakingResult& result) {
    double sum = 0.0;
    for (const TextureView& view : scene_.views) {
      sum += CompareThroughView(raycaster_, view, result.textured, Eigen::Vector2d::Zero(), 0.0).mean;
    }
    return sum / double(scene_.views.size());
  };
  const TextureBakingResult plain = bake(TexelBlend::kSingle, false);
  const TextureBakingResult levelled = bake(TexelBlend::kSingle, true);
  EXPECT_FALSE(plain.summary.levelling.enabled);
  ASSERT_GT(levelled.summary.levelling.num_seam_points, 100u);
  // The seam steps the levelling saw, before and after its corrections...
  EXPECT_GT(levelled.summary.levelling.step_before, 0.01);
  EXPECT_LT(levelled.summary.levelling.step_after, 0.25 * levelled.summary.levelling.step_before);
  // ... and in the texture, measured independently (each side through its own texture coordinates).
  EXPECT_GT(plain.summary.seams.Excess(), 0.01);
  EXPECT_LT(levelled.summary.seams.Excess(), 0.3 * plain.summary.seams.Excess());
  // The charts move towards each other, not away from the truth: the error against the true albedo
  // (whose scale no view knows better than the others) does not grow.
  EXPECT_LT(error(levelled), 1.05 * error(plain));

  // Fused, both sides of a border mix the same views: there is hardly a step, and levelling leaves it so.
  const TextureBakingResult fused = bake(TexelBlend::kFuse, false);
  const TextureBakingResult fused_levelled = bake(TexelBlend::kFuse, true);
  EXPECT_LT(fused_levelled.summary.levelling.step_before, 0.1 * levelled.summary.levelling.step_before);
  EXPECT_LT(fused_levelled.summary.levelling.step_after, fused_levelled.summary.levelling.step_before + 0.001);
  EXPECT_LT(fused_levelled.summary.seams.Excess(), std::max(fused.summary.seams.Excess(), 0.0) + 0.002);
  EXPECT_LT(error(fused_levelled), 1.05 * error(fused));
}

TEST_F(TextureBakerTest, TheResultDoesNotDependOnThreadsOrMemoryLimit) {
  TextureBakingOptions options;
  options.num_threads = 1;
  const TextureBakingResult one = BakeTexture(scene_.mesh, scene_.views, source_, options);
  options.num_threads = 2;
  options.fusion.memory_limit_bytes = 200 * 1024;  // forces several passes over the views
  const TextureBakingResult two = BakeTexture(scene_.mesh, scene_.views, source_, options);
  EXPECT_EQ(one.summary.fusion.num_passes, 1);
  EXPECT_GT(two.summary.fusion.num_passes, 1);  // one per batch of charts
  EXPECT_EQ(one.summary.num_texels, two.summary.num_texels);
  EXPECT_EQ(one.summary.fusion.num_texels, two.summary.num_texels);
  EXPECT_EQ(one.summary.fusion.texels_without_samples, two.summary.fusion.texels_without_samples);
  EXPECT_EQ(one.summary.fusion.rejected_samples, two.summary.fusion.rejected_samples);
  ASSERT_EQ(one.textured.pages.size(), two.textured.pages.size());
  for (std::size_t p = 0; p < one.textured.pages.size(); ++p) {
    ASSERT_EQ(one.textured.pages[p].size(), two.textured.pages[p].size());
    EXPECT_EQ(cv::norm(one.textured.pages[p], two.textured.pages[p], cv::NORM_INF), 0.0);
  }
  EXPECT_EQ(one.textured.face_page, two.textured.face_page);
}

TEST_F(TextureBakerTest, TexelSizeSetsTheAtlasResolution) {
  TextureBakingOptions options;
  options.charts.texel_size = 0.02;  // 2 cm: the textured ~2 x 2 m of floor is about 100 x 100 texels
  const TextureBakingResult coarse = BakeTexture(scene_.mesh, scene_.views, source_, options);
  options.charts.texel_size = 0.01;
  const TextureBakingResult fine = BakeTexture(scene_.mesh, scene_.views, source_, options);
  const double ratio = double(fine.summary.num_texels) / double(coarse.summary.num_texels);
  EXPECT_GT(ratio, 3.0);  // 4 x the surface texels (less the border texels, which grow only 2 x)
  EXPECT_LT(ratio, 4.5);
  EXPECT_GT(coarse.summary.num_texels, 0.5 * 100 * 100);
  EXPECT_LT(coarse.summary.num_texels, 2.0 * 100 * 100);
}

// A tiled bake's coarser level (texture_transfer.h): a coarser mesh of the same floor, textured from the
// fine texture halved, shows the true albedo as well as a texture baked for it from the images.
TEST_F(TextureBakerTest, ACoarserMeshTexturedFromTheTextureShowsTheTrueAlbedo) {
  TextureBakingOptions options;
  options.charts.texel_size = 0.005;
  const TextureBakingResult fine = BakeTexture(scene_.mesh, scene_.views, source_, options);
  const TexturedMesh halved = HalveTexture(fine.textured);
  ASSERT_EQ(halved.pages.size(), fine.textured.pages.size());
  EXPECT_EQ(halved.pages[0].cols, (fine.textured.pages[0].cols + 1) / 2);
  // Another tessellation of the floor: its vertices are not the fine mesh's and lie up to ~1 mm off it.
  const Mesh coarse_mesh = MakeHeightFieldMesh(
      [](double x, double y) { return 0.08 * std::sin(2.0 * x) * std::cos(1.5 * y); }, -1.0, 1.0, -1.0, 1.0, 23, 23);
  options.charts.texel_size = 0.01;
  options.num_threads = 1;
  const TransferredTexture one =
      TransferTexture({{&halved, &fine.view_of_face}}, coarse_mesh, scene_.views, 0.02, options);
  options.num_threads = 2;
  const TransferredTexture two =
      TransferTexture({{&halved, &fine.view_of_face}}, coarse_mesh, scene_.views, 0.02, options);
  const RaycastScene coarse_raycaster(coarse_mesh);
  const TextureBakingResult direct = BakeTexture(coarse_mesh, scene_.views, source_, options);
  EXPECT_GT(one.textured.NumTexturedFaces(), 0.95 * double(direct.textured.NumTexturedFaces()));
  for (std::size_t v = 0; v < scene_.views.size(); v += 4) {
    const RenderBackError transferred =
        CompareThroughView(coarse_raycaster, scene_.views[v], one.textured, Eigen::Vector2d::Zero(), 0.0);
    const RenderBackError baked =
        CompareThroughView(coarse_raycaster, scene_.views[v], direct.textured, Eigen::Vector2d::Zero(), 0.0);
    EXPECT_LT(transferred.median, 0.002) << scene_.views[v].name;
    // Two resamplings blur the patch borders a little more than one.
    EXPECT_LT(transferred.mean, 1.5 * baked.mean + 0.002) << scene_.views[v].name;
  }
  // The threads do not change the result.
  EXPECT_EQ(one.view_of_face, two.view_of_face);
  ASSERT_EQ(one.textured.pages.size(), two.textured.pages.size());
  for (std::size_t p = 0; p < one.textured.pages.size(); ++p) {
    EXPECT_EQ(cv::norm(one.textured.pages[p], two.textured.pages[p], cv::NORM_INF), 0.0);
  }
  // Nothing under the coarse mesh within the search distance: nothing textured.
  Mesh lifted = coarse_mesh;
  for (Eigen::Vector3d& vertex : lifted.vertices) vertex.z() += 0.5;
  const TransferredTexture none = TransferTexture({{&halved, &fine.view_of_face}}, lifted, scene_.views, 0.02, options);
  EXPECT_EQ(none.textured.NumTexturedFaces(), 0u);
}

}  // namespace
}  // namespace lutex
