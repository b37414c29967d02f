#pragma once

// Lights rigidly attached to the camera, for the forward simulator. Units follow Blender Cycles (the
// shared ground-truth renders): a light's radiant intensity I [render units / sr] on its axis gives a
// Lambertian surface of albedo rho at distance d and incidence angle i the radiance
// rho / pi * I * f(psi) * cos(i) / d^2 (in air), with f the angular profile at angle psi from the axis.
// A Cycles point or spot light of power P [W] has I = P / (4 pi).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lutex {

enum class BeamProfile {
  kIsotropic,    // f = 1
  kCosinePower,  // f = cos(psi)^exponent for psi < 90 degrees, else 0
  kGaussian,     // f = exp(-psi^2 / (2 sigma^2)), sigma in radians
  kCyclesSpot,   // Blender 3.4 spot: see CyclesSpotProfile
};

struct Light {
  std::string name;
  Eigen::Vector3d position_in_cam = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction_in_cam = Eigen::Vector3d::UnitZ();  // beam axis (unit)
  Eigen::Vector3d intensity = Eigen::Vector3d::Ones();          // on-axis radiant intensity per RGB channel
  BeamProfile profile = BeamProfile::kIsotropic;
  double exponent = 1.0;        // kCosinePower
  double sigma_rad = 0.5;       // kGaussian
  double spot_size_rad = 1.92;  // kCyclesSpot: full cone angle
  double spot_blend = 0.5;      // kCyclesSpot

  // f(psi) for cos(psi) = cos_psi.
  double Profile(double cos_psi) const;
};

// The profile's name in files (scene descriptions, LUT headers): "isotropic", "cosine_power", "gaussian",
// "cycles_spot"; and back, nothing for an unknown name.
const char* BeamProfileName(BeamProfile profile);
std::optional<BeamProfile> BeamProfileFromName(const std::string& name);

// Blender 3.4 Cycles spot profile: c0 = cos(size / 2), smooth = (1 - c0) * blend; 0 if cos psi <= c0,
// else cos psi * smoothstep((cos psi - c0) / smooth) while cos psi - c0 < smooth, else cos psi.
double CyclesSpotProfile(double cos_psi, double spot_size_rad, double spot_blend);

struct LightRig {
  std::vector<Light> lights;
};

// A single isotropic point light at the camera centre: the paper's rig for pre-rendering the LUT that
// sets the calibration weights.
LightRig PointLightAtCamera(double intensity = 1.0);

}  // namespace lutex
