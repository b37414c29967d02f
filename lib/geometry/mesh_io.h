#pragma once

// Reading and writing meshes by extension: PLY with lutex's own double-precision reader (ply_io.h:
// ascii and binary, faces as `vertex_indices` or `vertex_index`, extra properties ignored); OBJ, OFF and
// STL through OpenMesh (single precision). Polygons are triangulated. Per-vertex colours and texture
// coordinates, and per-corner texture coordinates, are kept when the file has them.

#include <filesystem>

#include "lib/geometry/mesh.h"

namespace lutex {

// Throws std::runtime_error naming `path` when the file is missing, not a mesh of a supported format,
// empty, or has non-finite vertices or out-of-range indices. Degenerate faces are dropped and counted in
// the log.
Mesh ReadMesh(const std::filesystem::path& path);

// Writes by extension (.ply is binary little-endian). Written to a temporary name and renamed.
void WriteMesh(const Mesh& mesh, const std::filesystem::path& path);

}  // namespace lutex
