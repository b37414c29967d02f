#pragma once

// Writes a textured mesh by the output's extension: .glb or .gltf (gltf_export.h), .obj (obj_export.h),
// .ply (textured_ply_export.h, single page).

#include <filesystem>
#include <vector>

#include "lib/image/image_io.h"
#include "texturing/gltf_export.h"
#include "texturing/textured_mesh.h"

namespace lutex {

// The files written, the model first. `page_encoding` applies to OBJ and PLY pages (glTF's base colour
// is always 8-bit sRGB), `gltf` to glTF (and CheckOutput refuses it for another format before any work).
std::vector<std::filesystem::path> WriteTexturedMesh(const TexturedMesh& textured, const std::filesystem::path& path,
                                                     ImageEncoding page_encoding = ImageEncoding::kSrgb8,
                                                     const GltfOptions& gltf = {});

// Throws std::invalid_argument naming `path` when its extension is none of the above.
void CheckTexturedMeshPath(const std::filesystem::path& path);

}  // namespace lutex
