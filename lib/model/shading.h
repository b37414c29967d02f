#pragma once

// How lutex's image formation model shades a surface (image_formation.h): cos_theta at a surface point
// with a given normal, for the light(s) calibration and restoration assume. Recorded in the LUT
// (FrustumLutGrid::shading): restoring must shade as calibrating did.
//
// One light position (`light_in_cam`; the camera centre by default, the paper's choice; a single flash's
// position in air): cos_theta = n . omega, omega the unit vector from the point to that position.
//
// A rig (`rig` not empty: positions, axes, beam profiles and intensities of the lights, as in a scene
// description): cos_theta = sum_l E_l max(n . omega_l, 0) / sum_l E_l, the irradiance-weighted mean over
// the lights, with E_l = I_l f_l(psi_l) / r_l^2 the irradiance light l alone gives the point in air
// (I_l: mean of its RGB intensity). The signal is then alpha(x) rho cos_theta with alpha(x) = camera path
// x sum_l E_l (water loss on the light paths taken as equal between lights), a function of the point
// alone, which is what a LUT can hold. With one position alpha also depends on the surface's orientation
// wherever the lights do not shine equally: on the Blender ColorChecker tilted 25 degrees, near the edge of
// one spot's cone, 20 pp of error. Where no light of the rig reaches the point the camera centre is used.

#include <Eigen/Core>

#include "lib/model/light_rig.h"

namespace lutex {

struct Shading {
  Eigen::Vector3d light_in_cam = Eigen::Vector3d::Zero();
  LightRig rig;  // when not empty, replaces light_in_cam

  // cos_theta; negative for back faces with one light position, 0 with a rig.
  double Cosine(const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam) const;
  // The same in float for a unit normal (restoration: every pixel of every image, hence inline), equal
  // to float precision.
  float Cosine(const Eigen::Vector3f& point_in_cam, const Eigen::Vector3f& unit_normal_in_cam) const {
    if (!rig.lights.empty()) {
      return static_cast<float>(Cosine(Eigen::Vector3d(point_in_cam.cast<double>()), Eigen::Vector3d(unit_normal_in_cam.cast<double>())));
    }
    const Eigen::Vector3f to_light = light_in_cam.cast<float>() - point_in_cam;
    return unit_normal_in_cam.dot(to_light) / to_light.norm();
  }
  bool operator==(const Shading& other) const;
};

}  // namespace lutex
