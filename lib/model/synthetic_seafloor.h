#pragma once

// A procedural seafloor for examples and tests: an undulating height field over a rectangle, with
// boulders, coloured in patches of many distinct colours (per-vertex sRGB colours), so that surveys of
// it exercise correspondences and restoration. Deterministic for a seed.

#include <cstdint>

#include "lib/geometry/mesh.h"

namespace lutex {

struct SyntheticSeafloorOptions {
  double size_x = 10.0, size_y = 8.0;  // metres, centred on the origin
  double cell_size = 0.05;             // metres per grid cell
  double relief = 0.15;                // amplitude of the undulation, metres
  int num_boulders = 2;
  double patch_size = 0.4;             // metres per colour patch
  std::uint32_t seed = 7;
};

Mesh MakeSyntheticSeafloor(const SyntheticSeafloorOptions& options);

}  // namespace lutex
