#pragma once

// How much of the albedo range the known colours span, per channel, and what that leaves undetermined.
// alpha and beta of a channel are told apart by known colours of different albedo in that channel
// (I1 - I2 = alpha cos_theta (rho1 - rho2)), and alpha for bright surfaces is only measured, not
// extrapolated, where a bright target was seen. A channel is narrow when its brightest target is below
// 0.25 or its targets differ by less than 0.15: the Blender boards' blue (albedo 0.013 and 0.10) is, and
// on an asymmetric rig blue-rich ColorChecker patches came out 23-33 pp off for it (issue 20).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "lib/calibration/observations.h"

namespace lutex {

struct AlbedoSpan {
  std::size_t count = 0;  // known colours
  Eigen::Vector3d lowest = Eigen::Vector3d::Zero(), highest = Eigen::Vector3d::Zero();
};

AlbedoSpan SpanOfKnownColours(const std::vector<KnownColorObservation>& known_colors);

// One warning per narrow channel ("blue: the targets span albedo 0.013 to 0.100 only; ..."), naming what
// could fix it given what the calibration already has. Empty without known colours. In air there is no
// backscatter to tell apart, so only a dark channel is narrow.
std::vector<std::string> NarrowSpanWarnings(const AlbedoSpan& span, bool in_air, bool has_pure_water,
                                            bool has_correspondences);

}  // namespace lutex
