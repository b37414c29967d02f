#include "tests/support/test_scenes.h"

#include <algorithm>
#include <cmath>

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

FrustumLutGrid LutGrid(int nx, int ny, int nz, double z_near, double z_far, int width, int height) {
  FrustumLutGrid grid;
  grid.nx = nx;
  grid.ny = ny;
  grid.nz = nz;
  grid.z_near = z_near;
  grid.z_far = z_far;
  grid.image_width = width;
  grid.image_height = height;
  return grid;
}

std::vector<double> SortedConfidentErrors(const RestoredImage& restored, const Eigen::Vector3d& albedo) {
  std::vector<double> errors;
  for (int row = 0; row < restored.albedo.rows; ++row) {
    for (int col = 0; col < restored.albedo.cols; ++col) {
      for (int c = 0; c < 3; ++c) {
        if (restored.confidence.at<cv::Vec3f>(row, col)[c] < 0.5f) continue;
        errors.push_back(std::abs(restored.albedo.at<cv::Vec3f>(row, col)[c] - albedo[c]));
      }
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

}  // namespace lutex::testing
