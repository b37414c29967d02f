// The first hits of a few rays found in one pass over the faces (lib/raycast/few_ray_hits.h), against
// Embree's on the same mesh: rolling terrain with a boulder, rays straight down, slanted across many grid
// cells, grazing, from below, and missing.

#include "lib/raycast/few_ray_hits.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {
namespace {

TEST(FewRayHits, FindTheFirstHitsEmbreeFinds) {
  const Mesh mesh = MakeHeightFieldMesh(
      [](double x, double y) {
        return 0.4 * std::exp(-(x * x + (y - 0.3) * (y - 0.3)) / 0.05) + 0.05 * std::sin(4.0 * x) * std::cos(3.0 * y);
      },
      -2.0, 2.0, -1.5, 1.5, 160, 120);
  const RaycastScene scene(mesh);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Ray3d> rays;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d origin(2.5 * uniform(random), 2.0 * uniform(random), 1.0 + 0.5 * uniform(random));
    // Down, then ever more slanted (up to nearly horizontal), some with a length other than 1.
    const double slant = 3.0 * double(i % 100) / 100.0;
    const Eigen::Vector3d direction(slant * uniform(random), slant * uniform(random), -1.0);
    rays.push_back({origin, direction * (i % 3 == 0 ? 2.5 : 1.0)});
  }
  rays.push_back({Eigen::Vector3d(0.1, 0.2, -1.0), Eigen::Vector3d(0.0, 0.0, 1.0)});   // from below
  rays.push_back({Eigen::Vector3d(5.0, 5.0, 1.0), Eigen::Vector3d(0.0, 0.0, -1.0)});   // beside the mesh
  rays.push_back({Eigen::Vector3d(0.0, 0.0, 2.0), Eigen::Vector3d(0.0, 0.0, 1.0)});    // away from it
  const std::vector<double> distances = FirstHitDistances(mesh, rays);
  ASSERT_EQ(distances.size(), rays.size());
  int hits = 0, misses = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const RayHit hit = scene.Intersect(rays[r].origin, rays[r].direction);
    ASSERT_EQ(hit.hit, std::isfinite(distances[r])) << "ray " << r;
    if (!hit.hit) {
      ++misses;
      continue;
    }
    ++hits;
    // Embree's distance is in units of the direction's length, in float.
    EXPECT_NEAR(distances[r], hit.distance, 1e-5 * (1.0 + hit.distance)) << "ray " << r;
  }
  EXPECT_GT(hits, 120);  // of 303: the slanted ones leave the mesh
  EXPECT_GE(misses, 2);
}

TEST(FewRayHits, ARayWithNoDirectionIsRefused) {
  const Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0.0, 1.0, 0.0, 1.0, 2, 2);
  EXPECT_THROW(FirstHitDistances(mesh, {{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}}), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
