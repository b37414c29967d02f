#include "lib/calibration/forward_scatter_estimate.h"

#include <algorithm>
#include <cmath>

namespace lutex {

double MeasuredScattering(const WaterPrior& prior) {
  if (prior.in_air) return 0.0;
  const Eigen::Vector3d pure_water_absorption = WaterPreset("clear")->absorption;
  return std::max(0.0, (prior.signal_attenuation - pure_water_absorption).minCoeff());
}

std::string NearestWaterPreset(double measured) {
  // A measurement of 0 (a water fitted to attenuate less than pure water absorbs) is the clearest.
  const double log_measured = std::log(std::max(measured, 1e-3));
  std::string nearest;
  double nearest_distance = 0.0;
  for (const std::string& name : WaterPresetList()) {
    const double distance = std::abs(std::log(WaterPreset(name)->scattering.mean()) - log_measured);
    if (nearest.empty() || distance < nearest_distance) {
      nearest = name;
      nearest_distance = distance;
    }
  }
  return nearest;
}

ForwardScatter ForwardScatterToTakeOut(const WaterPrior& prior, const Water& reference) {
  ForwardScatter scatter;
  scatter.scattering = reference.scattering.cwiseMin(Eigen::Vector3d::Constant(MeasuredScattering(prior)));
  scatter.anisotropy_g = reference.anisotropy_g;
  return scatter;
}

}  // namespace lutex
