#pragma once

#include "lib/geometry/camera.h"

namespace lutex::testing {

// A 640x480 camera of the given model with realistic, clearly non-zero distortion.
Camera MakeCamera(CameraModelId model_id, std::uint32_t camera_id = 1);

}  // namespace lutex::testing
