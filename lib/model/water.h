#pragma once

// A homogeneous medium: per-channel absorption a and scattering b [1/m], attenuation c = a + b, and a
// Henyey-Greenstein phase function with anisotropy g. In air a = b = 0.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lutex {

struct Water {
  Eigen::Vector3d absorption = Eigen::Vector3d::Zero();
  Eigen::Vector3d scattering = Eigen::Vector3d::Zero();
  double anisotropy_g = 0.9;

  Eigen::Vector3d Attenuation() const { return absorption + scattering; }
  bool IsAir() const { return absorption.isZero() && scattering.isZero(); }

  static Water Air() { return Water(); }
};

// Named waters, the starting points users pick by name (`lutex calibrate --reference-water`):
//   "clear":   absorption 0.35 0.05 0.02, scattering 0.04 0.045 0.05 [1/m] (clear oceanic water), g 0.9
//   "coastal": absorption 0.45 0.12 0.25, scattering 0.35 0.40 0.38 [1/m], g 0.9
// Nothing for another name.
std::optional<Water> WaterPreset(const std::string& name);
// The names of the presets, clearest first.
std::vector<std::string> WaterPresetList();
// The same names as a phrase for messages: "clear or coastal".
std::string WaterPresetNames();

// Henyey-Greenstein phase function (normalised over the sphere: integrates to 1 over 4 pi sr) for the
// cosine of the angle between the incoming propagation direction and the scattered direction.
double HenyeyGreenstein(double cos_angle, double g);

}  // namespace lutex
