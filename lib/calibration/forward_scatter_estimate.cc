#include "lib/calibration/forward_scatter_estimate.h"

#include <algorithm>

namespace lutex {

double MeasuredScattering(const WaterPrior& prior) {
  if (prior.in_air) return 0.0;
  const Eigen::Vector3d pure_water_absorption = WaterPreset("clear")->absorption;
  return std::max(0.0, (prior.signal_attenuation - pure_water_absorption).minCoeff());
}

ForwardScatter ForwardScatterToTakeOut(const WaterPrior& prior, const Water& reference) {
  ForwardScatter scatter;
  scatter.scattering = reference.scattering.cwiseMin(Eigen::Vector3d::Constant(MeasuredScattering(prior)));
  scatter.anisotropy_g = reference.anisotropy_g;
  return scatter;
}

}  // namespace lutex
