#pragma once

// Observations shaded anew: every known colour and correspondence view keeps its surface normal, so its
// cos_theta can be recomputed for another shading (lib/model/shading.h) without casting or reading an
// image again. Calibration fits a rig to camera-shaded observations, then shades them with it.

#include "lib/calibration/observations.h"
#include "lib/model/shading.h"

namespace lutex {

// Recomputes cos_theta of every observation with `shading`, and drops known colours and correspondences
// (either view) that come out below `min_cos_theta` (grazing for that shading, or lit by none of its
// lights). Pure-water observations have no surface and are kept as they are.
void Reshade(const Shading& shading, double min_cos_theta, ObservationSet* observations);

}  // namespace lutex
