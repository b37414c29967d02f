#pragma once

// The model's up, for the glTF writers (texture, tiles): the frame's +z when the model is georeferenced,
// else opposite the cameras' mean viewing direction (lib/geometry/up_direction.h), unless the user names
// an axis.

#include <string>

#include <Eigen/Core>

#include "colmap_integration/stages/workspace_georeference.h"
#include "lib/geometry/sparse_model.h"

namespace lutex {

struct ModelUp {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // in the model's frame
  bool from_cameras = false;
};

// Throws OptionError when `up_axis` is none of auto, x, -x, y, -y, z, -z ({up_axis}).
void CheckUpAxis(const std::string& up_axis);

// Throws OptionError asking for {up_axis} when the cameras do not say.
ModelUp ResolveModelUp(const std::string& up_axis, const WorkspaceGeoreference& georeference, const SparseModel& model);

// "+z of the model (the georeferenced frame's)" and the like, for summaries.
std::string DescribeModelUp(const ModelUp& up, const WorkspaceGeoreference& georeference);

}  // namespace lutex
