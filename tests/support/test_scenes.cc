#include "tests/support/test_scenes.h"

namespace lutex::testing {

Water ClearWater() {
  Water water;
  water.absorption = Eigen::Vector3d(0.35, 0.05, 0.02);
  water.scattering = Eigen::Vector3d(0.04, 0.045, 0.05);
  water.anisotropy_g = 0.88;
  return water;
}

LightRig TwoCosineLights(double offset, double intensity, double exponent) {
  LightRig rig;
  for (double x : {-offset, offset}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0, 0);
    light.intensity = Eigen::Vector3d::Constant(intensity);
    light.profile = BeamProfile::kCosinePower;
    light.exponent = exponent;
    rig.lights.push_back(light);
  }
  return rig;
}

}  // namespace lutex::testing
