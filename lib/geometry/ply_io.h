#pragma once

// PLY meshes read and written by lutex itself, because survey meshes need double precision (OpenMesh
// reads PLY coordinates through float). Reading accepts ascii, binary_little_endian and
// binary_big_endian; vertex x, y, z of any numeric type; optional red, green, blue (uchar, or float in
// [0, 1]); optional nx, ny, nz shading normals; optional per-vertex texture coordinates (s/t, u/v or texture_u/texture_v); faces as a list
// named `vertex_indices` or `vertex_index` (polygons are split into triangle fans); an optional face list
// `texcoord` of 2 floats per corner (as COLMAP's texturer writes); optional face red, green, blue. Other elements and properties are
// skipped. Writing produces binary_little_endian with double positions.

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "lib/geometry/mesh.h"

namespace lutex {

// Throws std::runtime_error (without a file name) on a malformed header or truncated data.
Mesh ReadPly(std::istream& stream);
// `comments`: extra header comment lines (e.g. "TextureFile model.png", as COLMAP's texturer writes).
void WritePly(const Mesh& mesh, std::ostream& stream, const std::vector<std::string>& comments = {});

}  // namespace lutex
