#include "colmap_integration/stages/model_up.h"

#include <stdexcept>

#include "lib/geometry/up_direction.h"
#include "lib/util/option_error.h"

namespace lutex {

void CheckUpAxis(const std::string& up_axis) {
  if (up_axis != "auto" && !AxisFromName(up_axis)) {
    throw OptionError("{up_axis} must be auto, x, -x, y, -y, z or -z, not '" + up_axis + "'");
  }
}

ModelUp ResolveModelUp(const std::string& up_axis, const WorkspaceGeoreference& georeference, const SparseModel& model) {
  CheckUpAxis(up_axis);
  ModelUp result;
  if (up_axis != "auto") {
    result.up = *AxisFromName(up_axis);
  } else if (!georeference.georeference.IsSet()) {
    try {
      result.up = UpFromCameras(model);
    } catch (const std::invalid_argument& error) {
      throw OptionError(std::string(error.what()) + "; give the model's up axis with {up_axis}");
    }
    result.from_cameras = true;
  }
  return result;
}

std::string DescribeModelUp(const ModelUp& up, const WorkspaceGeoreference& georeference) {
  return DirectionName(up.up) + " of the model" +
         (up.from_cameras                                                               ? " (opposite the cameras' mean viewing direction)"
          : georeference.georeference.IsSet() && up.up == Eigen::Vector3d::UnitZ() ? " (the georeferenced frame's)"
                                                                                     : " (as given)");
}

}  // namespace lutex
