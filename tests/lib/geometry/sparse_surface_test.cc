#include "lib/geometry/sparse_surface.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/median.h"

namespace lutex {
namespace {

// A rolling seafloor with a slope, 10 x 6 m.
double Terrain(double x, double y) { return 0.3 * std::sin(x) * std::cos(0.7 * y) + 0.05 * x; }

// A lawnmower survey at 2 m (3 lines, 11 images each, 640 x 480, f = 400 px) over the terrain, and
// sparse points as COLMAP would give them: on the terrain with 5 mm noise, each seen by 3 images with a
// 0.5 px error; then faults: 5 % gross outliers (0.3-1 m off), points with short tracks or large errors,
// and points far outside every image.
SparseModel SurveyModel(const std::function<double(double, double)>& terrain, int num_points, std::uint32_t seed) {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 640, 480, 400.0, 400.0);
  std::uint32_t id = 1;
  for (double y : {-2.0, 0.0, 2.0}) {
    for (int i = 0; i <= 10; ++i) {
      Image image;
      image.image_id = id++;
      image.camera_id = 1;
      image.name = "img" + std::to_string(image.image_id) + ".png";
      const double x = -4.5 + 0.9 * i;
      image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(x, y, terrain(x, y) + 2.0), Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(0, -1, 0));
      model.images[image.image_id] = image;
    }
  }
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> along(-5.5, 5.5), across(-3.0, 3.0), gross(0.3, 1.0);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::uniform_int_distribution<std::uint32_t> image(1, id - 3);
  std::uint64_t point_id = 1;
  const auto add = [&](const Eigen::Vector3d& xyz, int track, double error) {
    Point3D point;
    point.point3D_id = point_id;
    point.xyz = xyz;
    point.error = error;
    const std::uint32_t first = image(random);
    for (int k = 0; k < track; ++k) point.track.push_back({first + static_cast<std::uint32_t>(k), 0});
    model.points3D[point_id++] = point;
  };
  for (int i = 0; i < num_points; ++i) {
    const double x = along(random), y = across(random);
    const bool outlier = i % 20 == 0;
    add({x, y, terrain(x, y) + noise(random) + (outlier ? gross(random) * (i % 40 == 0 ? 1 : -1) : 0.0)}, 3, 0.5);
  }
  for (int i = 0; i < 50; ++i) add({along(random), across(random), 5.0}, 2, 0.5);   // short tracks
  for (int i = 0; i < 50; ++i) add({along(random), across(random), -5.0}, 4, 6.0);  // large errors
  for (int i = 0; i < 5; ++i) add({1000.0 + i, 1000.0, 0.0}, 3, 0.5);               // far outside every image
  return model;
}

TEST(SparseSurface, FitsATerrainFromNoisyPointsWithOutliersAndCoversItsFootprint) {
  const SparseModel model = SurveyModel(Terrain, 6000, 7);
  const SparseSurface surface = SurfaceFromSparsePoints(model, Eigen::Vector3d::UnitZ(), SparseSurfaceOptions());
  const SparseSurfaceSummary& summary = surface.summary;
  EXPECT_EQ(summary.short_tracks, 50u);
  EXPECT_EQ(summary.large_errors, 50u);
  EXPECT_GE(summary.outside_footprint, 5u);
  EXPECT_GE(summary.outliers, 250u);  // the 300 gross ones, most of them
  EXPECT_LT(summary.outliers, 450u);
  EXPECT_EQ(summary.steep_cells, 0u);
  EXPECT_LT(double(summary.layered_cells), 0.01 * double(summary.footprint_cells));
  // Heights against the truth, over the surveyed area (depth from 2 m: 1 % is 2 cm).
  std::vector<double> errors;
  for (const Eigen::Vector3d& v : surface.mesh.vertices) {
    if (std::abs(v.x()) < 4.5 && std::abs(v.y()) < 2.5) errors.push_back(std::abs(v.z() - Terrain(v.x(), v.y())));
  }
  ASSERT_GT(errors.size(), 100u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p95 = errors[errors.size() * 95 / 100];
  std::printf("sparse surface: %.3f m cells, %zu faces, height error median %.1f mm, p95 %.1f mm\n",
              summary.resolution, summary.num_faces, 1000.0 * median, 1000.0 * p95);
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p95, 0.03);
  // Every point of the surveyed area has the surface below it.
  const RaycastScene scene(surface.mesh);
  int hits = 0, rays = 0;
  for (double x = -4.4; x <= 4.4; x += 0.1) {
    for (double y = -2.4; y <= 2.4; y += 0.1) {
      ++rays;
      hits += scene.Intersect(Eigen::Vector3d(x, y, 10.0), Eigen::Vector3d(0, 0, -1)).hit;
    }
  }
  EXPECT_GE(double(hits), 0.98 * rays);
  // Nothing far outside the images.
  EXPECT_LT(surface.mesh.BoundsMax().x(), 10.0);
}

TEST(SparseSurface, ACliffIsReportedAsNotTwoAndAHalfD) {
  const auto cliff = [](double x, double) { return x > 0.0 ? 1.0 : 0.0; };
  const SparseSurface surface = SurfaceFromSparsePoints(SurveyModel(cliff, 6000, 3), Eigen::Vector3d::UnitZ(),
                                                        SparseSurfaceOptions());
  EXPECT_GT(surface.summary.steep_cells + surface.summary.layered_cells, 5u);
}

TEST(SparseSurface, TheModelsUpNeedNotBeZ) {
  // The same survey in a frame where up is -y (an unaligned COLMAP model).
  SparseModel model = SurveyModel(Terrain, 3000, 11);
  const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitY());
  for (auto& [id, point] : model.points3D) point.xyz = turn * point.xyz;
  for (auto& [id, image] : model.images) {
    image.cam_from_world = Rigid3d(image.cam_from_world.rotation * turn.inverse(), image.cam_from_world.translation);
  }
  const SparseSurface surface = SurfaceFromSparsePoints(model, -Eigen::Vector3d::UnitY(), SparseSurfaceOptions());
  std::vector<double> errors;
  for (const Eigen::Vector3d& v : surface.mesh.vertices) {
    const Eigen::Vector3d level = turn.inverse() * v;
    if (std::abs(level.x()) < 4.5 && std::abs(level.y()) < 2.5) errors.push_back(std::abs(level.z() - Terrain(level.x(), level.y())));
  }
  ASSERT_GT(errors.size(), 100u);
  EXPECT_LT(MedianInPlace(errors), 0.015);
}

TEST(SparseSurface, BadModelsAreClearErrors) {
  SparseModel empty = SurveyModel(Terrain, 0, 1);
  empty.points3D.clear();
  try {
    SurfaceFromSparsePoints(empty, Eigen::Vector3d::UnitZ(), SparseSurfaceOptions());
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("no 3-D points"), std::string::npos) << error.what();
  }
  SparseModel line = SurveyModel(Terrain, 0, 1);
  line.points3D.clear();
  for (std::uint64_t i = 1; i <= 100; ++i) {
    Point3D point;
    point.xyz = {-4.0 + 0.08 * double(i), 0.0, 0.0};
    point.error = 0.5;
    point.track = {{1, 0}, {2, 0}, {3, 0}};
    line.points3D[i] = point;
  }
  try {
    SurfaceFromSparsePoints(line, Eigen::Vector3d::UnitZ(), SparseSurfaceOptions());
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("on a line"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lutex
