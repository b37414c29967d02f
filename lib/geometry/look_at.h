#pragma once

// Camera poses from where a camera is and where it looks, for synthetic scenes and surveys.

#include <Eigen/Core>

#include "lib/geometry/rigid3d.h"

namespace lutex {

// cam_from_world of a camera at `centre_in_world` whose optical axis (camera +z) points along
// `forward_in_world` and whose image "down" (camera +y) is as close as possible to `down_in_world`.
// `forward_in_world` and `down_in_world` must not be parallel.
Rigid3d CamFromWorldLookingAt(const Eigen::Vector3d& centre_in_world, const Eigen::Vector3d& forward_in_world,
                              const Eigen::Vector3d& down_in_world);

}  // namespace lutex
