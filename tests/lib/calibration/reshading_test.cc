// Observations shaded anew keep their normals: cos_theta is recomputed for the new shading, and those
// the new lights graze are dropped (a correspondence when either view is).

#include <cmath>

#include <gtest/gtest.h>

#include "lib/calibration/reshading.h"

namespace lutex {
namespace {

TEST(Reshading, CosThetaFollowsTheNewShadingAndGrazedObservationsGo) {
  ObservationSet observations;
  KnownColorObservation facing, tilted;
  facing.point_in_cam = Eigen::Vector3d(0, 0, 2);
  facing.normal_in_cam = Eigen::Vector3d(0, 0, -1);
  facing.cos_theta = 1.0;
  tilted.point_in_cam = Eigen::Vector3d(0, 0, 2);
  tilted.normal_in_cam = Eigen::Vector3d(std::sin(1.2), 0, -std::cos(1.2));  // 69 degrees towards +x
  tilted.cos_theta = std::cos(1.2);
  observations.known_colors = {facing, tilted};
  CorrespondenceObservation pair;
  pair.first.point_in_cam = pair.second.point_in_cam = Eigen::Vector3d(0, 0, 2);
  pair.first.normal_in_cam = facing.normal_in_cam;
  pair.second.normal_in_cam = tilted.normal_in_cam;
  observations.correspondences = {pair};
  observations.pure_water.resize(3);

  // One light 2 m to the -x side: the facing point sees it at 45 degrees, the tilted one at 114 (behind).
  Shading shading;
  shading.light_in_cam = Eigen::Vector3d(-2, 0, 0);
  Reshade(shading, 0.3, &observations);
  ASSERT_EQ(observations.known_colors.size(), 1u);
  EXPECT_NEAR(observations.known_colors[0].cos_theta, std::cos(M_PI / 4), 1e-12);
  EXPECT_TRUE(observations.correspondences.empty());
  EXPECT_EQ(observations.pure_water.size(), 3u);
}

}  // namespace
}  // namespace lutex
