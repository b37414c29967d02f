#pragma once

// A ChArUco board with six coloured patches (three above the squares, three below) for tests, and its
// mesh: the board frame's plane z = 0 in cells of an eighth of a square, coloured as printed (patches,
// black squares, marker bits, white margin), face colours 8-bit sRGB.

#include "lib/calibration/charuco_target.h"
#include "lib/geometry/mesh.h"

namespace lutex::testing {

// 6 x 4 squares of `square` metres, markers of 4 x 4 bits (DICT_4X4_50) 6/8 of a square, patches 1.5
// squares wide.
CharucoSpec PatchedCharucoSpec(double square);

Mesh CharucoBoardMesh(const CharucoSpec& spec);

}  // namespace lutex::testing
