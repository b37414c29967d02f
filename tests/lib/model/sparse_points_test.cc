#include "lib/model/sparse_points.h"

#include <cmath>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/geometry/sparse_surface.h"
#include "lib/util/median.h"

namespace lutex {
namespace {

double Terrain(double x, double y) { return 0.2 * std::sin(1.3 * x) * std::cos(0.9 * y); }

// Two lines of six images at 2 m over the terrain.
SparseModel Survey() {
  SparseModel model;
  model.cameras[1] = Camera::Pinhole(1, 320, 240, 200.0, 200.0);
  std::uint32_t id = 1;
  for (double y : {-0.6, 0.6}) {
    for (int i = 0; i < 6; ++i) {
      Image image;
      image.image_id = id++;
      image.camera_id = 1;
      image.name = "img" + std::to_string(image.image_id) + ".png";
      image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(-2.0 + 0.8 * i, y, 2.0), Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(0, -1, 0));
      model.images[image.image_id] = image;
    }
  }
  return model;
}

TEST(SimulatedSparsePoints, LieOnTheSurfaceAndReprojectIntoEveryImageOfTheirTrack) {
  const Mesh mesh = MakeHeightFieldMesh(Terrain, -5, 5, -4, 4, 200, 160);
  const RaycastScene scene(mesh);
  SparseModel model = Survey();
  SparsePointsOptions options;
  options.points_per_image = 400;
  const std::size_t added = AddSimulatedSparsePoints(scene, options, &model);
  EXPECT_GT(added, 3000u);  // most of the 12 x 400 points are seen twice or more
  EXPECT_EQ(model.points3D.size(), added);
  std::size_t observations = 0;
  for (const auto& [id, point] : model.points3D) {
    ASSERT_GE(point.track.size(), 2u);
    EXPECT_NEAR(point.xyz.z(), Terrain(point.xyz.x(), point.xyz.y()), 2e-3);  // on the (faceted) surface
    EXPECT_EQ(point.error, 0.0);
    for (const TrackElement& element : point.track) {
      const Image& image = model.images.at(element.image_id);
      const Point2D& observation = image.points2D.at(element.point2D_idx);
      EXPECT_EQ(observation.point3D_id, id);
      const Eigen::Vector2d projected = model.cameras.at(1).ImgFromCam(image.cam_from_world * point.xyz);
      EXPECT_LT((projected - observation.xy).norm(), 1e-6);
      ++observations;
    }
  }
  EXPECT_GT(double(observations) / double(added), 2.5);  // neighbouring images overlap
  // Deterministic: the same points again.
  SparseModel again = Survey();
  AddSimulatedSparsePoints(scene, options, &again);
  ASSERT_EQ(again.points3D.size(), model.points3D.size());
  EXPECT_EQ(again.points3D.begin()->second.xyz, model.points3D.begin()->second.xyz);
}

TEST(SimulatedSparsePoints, ANoisySurveyGivesASurfaceWithinItsNoise) {
  const Mesh mesh = MakeHeightFieldMesh(Terrain, -5, 5, -4, 4, 200, 160);
  const RaycastScene scene(mesh);
  SparseModel model = Survey();
  SparsePointsOptions options;
  options.points_per_image = 900;
  options.noise = 0.003;
  AddSimulatedSparsePoints(scene, options, &model);
  const SparseSurface surface = SurfaceFromSparsePoints(model, Eigen::Vector3d::UnitZ(), SparseSurfaceOptions());
  std::vector<double> errors;
  for (const Eigen::Vector3d& v : surface.mesh.vertices) {
    if (std::abs(v.x()) < 2.0 && std::abs(v.y()) < 0.8) errors.push_back(std::abs(v.z() - Terrain(v.x(), v.y())));
  }
  ASSERT_GT(errors.size(), 50u);
  EXPECT_LT(MedianInPlace(errors), 0.004);
}

}  // namespace
}  // namespace lutex
