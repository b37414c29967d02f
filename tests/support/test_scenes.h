#pragma once

// Water, light rigs, LUT grids and restoration checks that several tests share.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/calibration/observations.h"
#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"
#include "lib/lut/frustum_lut.h"
#include "lib/model/simulator.h"
#include "lib/model/light_rig.h"
#include "lib/model/water.h"
#include "lib/restoration/restorer.h"

namespace lutex::testing {

// Jerlov oceanic IA-like clear water, as in the shared Blender datasets.
Water ClearWater();

// Two lights at (+-offset, 0, 0) in the camera frame, looking forward, cos^exponent beams.
LightRig TwoCosineLights(double offset, double intensity, double exponent);

// A LUT grid of nx x ny cells and nz slabs over [z_near, z_far] for width x height images (the other
// fields at their defaults).
FrustumLutGrid LutGrid(int nx, int ny, int nz, double z_near, double z_far, int width, int height);

// |restored albedo - albedo| over every pixel-channel the restoration trusts (confidence >= 0.5), sorted.
std::vector<double> SortedConfidentErrors(const RestoredImage& restored, const Eigen::Vector3d& albedo);

// A simulated frame as a camera delivers it: the render through a noisy sensor (exposure 2, shot noise
// 0.01, read noise 0.002; noise seed `seed`, frame `index`), written as 8-bit sRGB PNG into `folder` and
// read back as linear RGB.
cv::Mat NoisySrgb8Frame(const Simulator& simulator, const CameraRays& rays, const Rigid3d& cam_from_world,
                        std::uint64_t index, std::uint64_t seed, const std::filesystem::path& folder);

// How well a board's known colours alone calibrate: a LUT of 8 x 6 cells and 6 slabs over z_near .. z_far
// (levels 2 x 2, 4 x 3, 8 x 6; weights from a point light at the camera in clear water) fitted to
// `observations`, then a held-out grey plane (albedo 0.35; two cosine lights 0.3 m beside the camera,
// clear water) seen from `eye` along `forward` restored with it: the sorted confident errors.
std::vector<double> HeldOutGreyPlaneErrors(const ObservationSet& observations, const Camera& camera, double z_near,
                                           double z_far, const Eigen::Vector3d& eye, const Eigen::Vector3d& forward,
                                           const std::filesystem::path& folder);

}  // namespace lutex::testing
