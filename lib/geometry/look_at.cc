#include "lib/geometry/look_at.h"

#include <Eigen/Geometry>

namespace lutex {

Rigid3d CamFromWorldLookingAt(const Eigen::Vector3d& centre_in_world, const Eigen::Vector3d& forward_in_world,
                              const Eigen::Vector3d& down_in_world) {
  const Eigen::Vector3d z = forward_in_world.normalized();
  const Eigen::Vector3d x = down_in_world.cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_from_cam_rotation;
  world_from_cam_rotation << x, y, z;
  const Eigen::Matrix3d cam_from_world_rotation = world_from_cam_rotation.transpose();
  return Rigid3d(Eigen::Quaterniond(cam_from_world_rotation), -(cam_from_world_rotation * centre_in_world));
}

}  // namespace lutex
