#pragma once

// Wavefront OBJ export of a textured mesh, for MeshLab, CloudCompare and GIS tools: MODEL.obj (vertices
// in double precision, per-corner texture coordinates with v up, vertex normals), MODEL.mtl (one
// material per page, unlit: Kd 1 with the page as map_Kd, illum 0) and MODEL_page_N.png. Faces no view
// saw use a material of neutral grey without texture.

#include <filesystem>

#include "lib/image/image_io.h"
#include "texturing/textured_mesh.h"

namespace lutex {

// `page_encoding`: kSrgb8 (what viewers expect) or kLinear16 (albedo without 8-bit quantisation).
// Every file is written to a temporary name and renamed; throws naming the file that fails.
void WriteObj(const TexturedMesh& textured, const std::filesystem::path& path,
              ImageEncoding page_encoding = ImageEncoding::kSrgb8);

}  // namespace lutex
