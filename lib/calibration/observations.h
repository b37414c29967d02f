#pragma once

// What the calibration fits the LUT to (paper Sec. 2.2). Every observation carries its pixel, its 3-D
// point in the camera frame (planar depth z = point.z()), its colour, its shading and its weight, and the
// image it was seen in (`image`, an index into ObservationSet::images; -1 when not known), so that one
// exposure gain per image can be fitted and divided out (exposure_gains.h).

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace lutex {

// A pixel seeing a surface of known albedo: I = alpha(x) cos_theta rho + beta(x)   (paper Eq. 5).
struct KnownColorObservation {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector3d point_in_cam = Eigen::Vector3d::Zero();
  Eigen::Vector3d intensity = Eigen::Vector3d::Zero();  // linear RGB
  Eigen::Vector3d albedo = Eigen::Vector3d::Zero();     // linear RGB
  double cos_theta = 1.0;
  Eigen::Vector3d weight = Eigen::Vector3d::Ones();     // per channel (paper "Weights and Accuracy")
  Eigen::Vector3d normal_in_cam = Eigen::Vector3d::Zero();  // unit, facing the camera (what cos_theta is of)
  int image = -1;
};

// A pixel of a pure-water image: backscatter only, so beta along its ray is at most the observed value at
// every slab (paper Eq. "beta_N <= I_pw").
struct PureWaterObservation {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector3d intensity = Eigen::Vector3d::Zero();
  double weight = 1.0;
  int image = -1;
};

// One image's view of a surface point of unknown albedo.
struct SurfaceView {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector3d point_in_cam = Eigen::Vector3d::Zero();
  Eigen::Vector3d intensity = Eigen::Vector3d::Zero();  // linear RGB
  double cos_theta = 1.0;
  Eigen::Vector3d normal_in_cam = Eigen::Vector3d::Zero();  // unit, facing the camera (what cos_theta is of)
  int image = -1;
};

// The same surface point seen by two images (paper Eq. 8 with lutex's shading): its albedo
// (I - beta) / (alpha cos_theta) is the same in both, so
//   alpha(x2) cos_theta2 (I1 - beta(x1)) - alpha(x1) cos_theta1 (I2 - beta(x2)) = 0.
struct CorrespondenceObservation {
  SurfaceView first, second;
  Eigen::Vector3d weight = Eigen::Vector3d::Ones();  // per channel
};

struct ObservationSet {
  std::vector<KnownColorObservation> known_colors;
  std::vector<PureWaterObservation> pure_water;
  std::vector<CorrespondenceObservation> correspondences;
  // The images the observations were seen in; an observation's `image` indexes this list.
  std::vector<std::filesystem::path> images;
};

// Appends `part` to `into`: its images that `into` lists already (the same path) keep their index there,
// the others are added, and `part`'s observations are renumbered accordingly.
void MergeObservations(ObservationSet part, ObservationSet* into);

}  // namespace lutex
