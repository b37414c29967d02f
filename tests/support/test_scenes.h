#pragma once

// Water, light rigs, LUT grids and restoration checks that several tests share.

#include <vector>

#include <Eigen/Core>

#include "lib/lut/frustum_lut.h"
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

}  // namespace lutex::testing
