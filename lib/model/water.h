#pragma once

// A homogeneous medium: per-channel absorption a and scattering b [1/m], attenuation c = a + b, and a
// Henyey-Greenstein phase function with anisotropy g. In air a = b = 0.

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

// Henyey-Greenstein phase function (normalised over the sphere: integrates to 1 over 4 pi sr) for the
// cosine of the angle between the incoming propagation direction and the scattered direction.
double HenyeyGreenstein(double cos_angle, double g);

}  // namespace lutex
