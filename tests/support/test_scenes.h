#pragma once

// Water and light rigs that several tests share.

#include "lib/model/light_rig.h"
#include "lib/model/water.h"

namespace lutex::testing {

// Jerlov oceanic IA-like clear water, as in the shared Blender datasets.
Water ClearWater();

// Two lights at (+-offset, 0, 0) in the camera frame, looking forward, cos^exponent beams.
LightRig TwoCosineLights(double offset, double intensity, double exponent);

}  // namespace lutex::testing
