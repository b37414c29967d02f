#include "lib/geometry/up_direction.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lutex {

Eigen::Vector3d UpFromViewingDirections(const std::vector<Eigen::Vector3d>& viewing_directions_in_world,
                                        double snap_degrees) {
  if (viewing_directions_in_world.empty()) throw std::invalid_argument("no cameras to tell up from");
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& direction : viewing_directions_in_world) mean += direction.normalized();
  mean /= static_cast<double>(viewing_directions_in_world.size());
  if (!(mean.norm() >= 0.5)) {
    throw std::invalid_argument("the cameras look in too many directions to tell which way is up");
  }
  const Eigen::Vector3d up = -mean.normalized();
  Eigen::Index axis = 0;
  up.cwiseAbs().maxCoeff(&axis);
  Eigen::Vector3d snapped = Eigen::Vector3d::Zero();
  snapped[axis] = up[axis] > 0 ? 1.0 : -1.0;
  const double angle_degrees = std::acos(std::min(1.0, up.dot(snapped))) * 180.0 / M_PI;
  return angle_degrees <= snap_degrees ? snapped : up;
}

Eigen::Vector3d UpFromCameras(const SparseModel& model, double snap_degrees) {
  std::vector<Eigen::Vector3d> viewing_directions_in_world;
  for (const auto& [id, image] : model.images) {
    viewing_directions_in_world.push_back(image.cam_from_world.rotation.inverse() * Eigen::Vector3d::UnitZ());
  }
  return UpFromViewingDirections(viewing_directions_in_world, snap_degrees);
}

std::optional<Eigen::Vector3d> AxisFromName(const std::string& name) {
  const bool negative = !name.empty() && name[0] == '-';
  const std::string letter = negative || (!name.empty() && name[0] == '+') ? name.substr(1) : name;
  if (letter.size() != 1 || letter[0] < 'x' || letter[0] > 'z') return std::nullopt;
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  axis[letter[0] - 'x'] = negative ? -1.0 : 1.0;
  return axis;
}

std::string DirectionName(const Eigen::Vector3d& direction) {
  for (int i = 0; i < 3; ++i) {
    if (std::abs(std::abs(direction[i]) - 1.0) < 1e-12 && direction.cwiseAbs().sum() < 1.0 + 1e-12) {
      return std::string(direction[i] > 0 ? "+" : "-") + static_cast<char>('x' + i);
    }
  }
  char text[64];
  std::snprintf(text, sizeof(text), "(%.3f, %.3f, %.3f)", direction.x(), direction.y(), direction.z());
  return text;
}

}  // namespace lutex
