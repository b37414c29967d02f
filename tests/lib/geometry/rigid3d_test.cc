#include "lib/geometry/rigid3d.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

Rigid3d SomePose() {
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
                 Eigen::Vector3d(0.5, -1.0, 2.0));
}

TEST(Rigid3d, InverseUndoesTheTransform) {
  const Rigid3d cam_from_world = SomePose();
  const Eigen::Vector3d point_in_world(1.0, 2.0, 3.0);
  const Eigen::Vector3d point_in_cam = cam_from_world * point_in_world;
  EXPECT_LT((cam_from_world.Inverse() * point_in_cam - point_in_world).norm(), 1e-12);
}

TEST(Rigid3d, CompositionAppliesRightToLeft) {
  const Rigid3d b_from_a = SomePose();
  const Rigid3d c_from_b(Eigen::Quaterniond(Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(1, 1, 1));
  const Eigen::Vector3d point_in_a(-2.0, 0.5, 4.0);
  EXPECT_LT(((c_from_b * b_from_a) * point_in_a - c_from_b * (b_from_a * point_in_a)).norm(), 1e-12);
}

// The camera centre maps to the camera origin.
TEST(Rigid3d, TargetOriginInSourceIsTheCameraCentre) {
  const Rigid3d cam_from_world = SomePose();
  EXPECT_LT((cam_from_world * cam_from_world.TargetOriginInSource()).norm(), 1e-12);
}

TEST(Rigid3d, IsValidRejectsNanAndNonUnitQuaternions) {
  Rigid3d pose = SomePose();
  EXPECT_TRUE(pose.IsValid());
  pose.translation.x() = std::nan("");
  EXPECT_FALSE(pose.IsValid());
  pose = SomePose();
  pose.rotation.coeffs() *= 2.0;
  EXPECT_FALSE(pose.IsValid());
}

}  // namespace
}  // namespace lutex
