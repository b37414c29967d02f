#include "lib/model/light_rig.h"

#include <algorithm>
#include <cmath>

namespace lutex {

double CyclesSpotProfile(double cos_psi, double spot_size_rad, double spot_blend) {
  const double c0 = std::cos(spot_size_rad / 2.0);
  if (cos_psi <= c0) return 0.0;
  const double smooth = (1.0 - c0) * spot_blend;
  if (cos_psi - c0 < smooth) {
    const double t = std::clamp((cos_psi - c0) / smooth, 0.0, 1.0);
    return cos_psi * t * t * (3.0 - 2.0 * t);
  }
  return cos_psi;
}

const char* BeamProfileName(BeamProfile profile) {
  switch (profile) {
    case BeamProfile::kIsotropic: return "isotropic";
    case BeamProfile::kCosinePower: return "cosine_power";
    case BeamProfile::kGaussian: return "gaussian";
    case BeamProfile::kCyclesSpot: return "cycles_spot";
  }
  return "isotropic";
}

std::optional<BeamProfile> BeamProfileFromName(const std::string& name) {
  for (const BeamProfile profile : {BeamProfile::kIsotropic, BeamProfile::kCosinePower, BeamProfile::kGaussian,
                                    BeamProfile::kCyclesSpot}) {
    if (name == BeamProfileName(profile)) return profile;
  }
  return std::nullopt;
}

double Light::Profile(double cos_psi) const {
  switch (profile) {
    case BeamProfile::kIsotropic: return 1.0;
    case BeamProfile::kCosinePower: return cos_psi > 0.0 ? std::pow(cos_psi, exponent) : 0.0;
    case BeamProfile::kGaussian: {
      const double psi = std::acos(std::clamp(cos_psi, -1.0, 1.0));
      return std::exp(-psi * psi / (2.0 * sigma_rad * sigma_rad));
    }
    case BeamProfile::kCyclesSpot: return CyclesSpotProfile(cos_psi, spot_size_rad, spot_blend);
  }
  return 0.0;
}

LightRig PointLightAtCamera(double intensity) {
  LightRig rig;
  Light light;
  light.name = "point at camera";
  light.intensity = Eigen::Vector3d::Constant(intensity);
  rig.lights.push_back(light);
  return rig;
}

}  // namespace lutex
