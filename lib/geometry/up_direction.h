#pragma once

// Which way is up in a model, for viewers that assume one (glTF is +Y up). A model aligned to navigation
// data (ENU, UTM; the simulator's and Blender's scenes) is +Z up; a COLMAP model that was never aligned
// has whatever frame reconstruction gave it. Seafloor surveys look down, so up is opposite the cameras'
// mean viewing direction. When that lies within `snap_degrees` of a coordinate axis the model is taken to
// be aligned and up is that axis exactly (a slightly oblique survey does not tilt an aligned model); else
// it is the mean direction itself.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/sparse_model.h"

namespace lutex {

// `viewing_directions_in_world`: each camera's optical axis (+z of the camera) in the model's frame.
// Throws std::invalid_argument when there are none or they do not agree on a side (their mean is shorter
// than half a unit: cameras looking every way, up cannot be told); the caller then asks for --up-axis.
Eigen::Vector3d UpFromViewingDirections(const std::vector<Eigen::Vector3d>& viewing_directions_in_world,
                                        double snap_degrees = 10.0);

// The same from the optical axes of every registered image of `model`.
Eigen::Vector3d UpFromCameras(const SparseModel& model, double snap_degrees = 10.0);

// "x", "-x", "y", "-y", "z", "-z" as a unit axis; nothing for another text.
std::optional<Eigen::Vector3d> AxisFromName(const std::string& name);

// The inverse for axes ("+z", "-y"); a direction off the axes as "(x, y, z)".
std::string DirectionName(const Eigen::Vector3d& direction);

}  // namespace lutex
