#pragma once

// A rigid transform `target_from_source`: point_in_target = rotation * point_in_source + translation.
// COLMAP stores image poses as cam_from_world with the quaternion in (w, x, y, z) order.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lutex {

struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Rigid3d() = default;
  Rigid3d(const Eigen::Quaterniond& rotation_in, const Eigen::Vector3d& translation_in)
      : rotation(rotation_in), translation(translation_in) {}

  Eigen::Vector3d operator*(const Eigen::Vector3d& point_in_source) const {
    return rotation * point_in_source + translation;
  }
  // (c_from_b * b_from_a) = c_from_a.
  Rigid3d operator*(const Rigid3d& b_from_a) const {
    return Rigid3d(rotation * b_from_a.rotation, rotation * b_from_a.translation + translation);
  }
  // source_from_target.
  Rigid3d Inverse() const {
    const Eigen::Quaterniond inverse_rotation = rotation.inverse();
    return Rigid3d(inverse_rotation, -(inverse_rotation * translation));
  }
  // The target frame's origin in source coordinates: for cam_from_world, the camera centre in the world.
  Eigen::Vector3d TargetOriginInSource() const { return -(rotation.inverse() * translation); }

  // True when every coefficient is finite and the quaternion has unit norm (to 1e-6).
  bool IsValid() const;
};

}  // namespace lutex
