#include "lib/geometry/look_at.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

// A camera 2 m above the origin looking straight down with image-down along world -y: the origin is
// 2 m in front of it, and a point at world +x is to the right in the image (camera +x).
TEST(LookAt, DownLookingCamera) {
  const Rigid3d cam_from_world =
      CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
  EXPECT_LT((cam_from_world * Eigen::Vector3d(0, 0, 0) - Eigen::Vector3d(0, 0, 2)).norm(), 1e-12);
  EXPECT_LT((cam_from_world * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 0, 2)).norm(), 1e-12);
  EXPECT_LT((cam_from_world * Eigen::Vector3d(0, -1, 0) - Eigen::Vector3d(0, 1, 2)).norm(), 1e-12);
  EXPECT_LT((cam_from_world.TargetOriginInSource() - Eigen::Vector3d(0, 0, 2)).norm(), 1e-12);
}

}  // namespace
}  // namespace lutex
