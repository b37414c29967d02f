#pragma once

// The LUT file format (version 1), self-describing and versioned:
//
//   line 1: "LUTEX-LUT 1"
//   line 2: a one-line JSON header, e.g.
//     {"format":"lutex-lut","version":1,"nx":40,"ny":30,"nz":10,"z_near":0.5,"z_far":5.0,
//      "depth_spacing":"inverse_z","alpha_interpolation":"inverse_square","image_width":4000,"image_height":3000,
//      "node_layout":"slab k, then row j, then column i; per node alpha_r alpha_g alpha_b beta_r beta_g beta_b",
//      "value_type":"float64 little-endian","num_values":...}
//   then exactly num_values = (nx + 1) (ny + 1) nz 6 binary float64 values, nothing after them.
//
// Node (i, j, k) sits at pixel (i / nx * image_width, j / ny * image_height) and planar depth slab k;
// alpha_interpolation is "trilinear" or "inverse_square" (alpha * z^2 interpolated; see frustum_lut.h);
// shading_light_in_cam (optional, default [0, 0, 0]) is where the model's shading puts the light.
// Version 2 (magic "LUTEX-LUT 2", "version":2) is written only when shading uses a light rig
// (lib/model/shading.h) and adds "shading_rig": [{"position", "direction", "intensity": [3 numbers],
// "profile": "isotropic" | "cosine_power" | "gaussian" | "cycles_spot", "exponent", "sigma_rad",
// "spot_size_rad", "spot_blend"}, ...], so a lutex that cannot shade with a rig rejects the file instead
// of restoring with the wrong shading. Version 3 (magic "LUTEX-LUT 3", "version":3) is written only when
// the calibration took forward scattering out of its images (lib/model/forward_scatter.h) and adds
// "forward_scatter": {"scattering_per_m": [3 numbers], "anisotropy_g"}, which restoration must take out
// the same way (it may also hold "shading_rig"). Readers reject other versions, wrong value counts, truncation and
// non-finite values.

#include <filesystem>
#include <istream>
#include <ostream>

#include "lib/lut/frustum_lut.h"

namespace lutex {

FrustumLut ReadLut(std::istream& stream);
FrustumLut ReadLut(const std::filesystem::path& path);
void WriteLut(const FrustumLut& lut, std::ostream& stream);
void WriteLut(const FrustumLut& lut, const std::filesystem::path& path);

}  // namespace lutex
