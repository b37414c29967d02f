#pragma once

// PLY export of a textured mesh in the layout COLMAP's mesh texturer writes: the mesh's vertices and
// faces in their input order, a face list `texcoord` of 2 floats per corner (v up), a
// `comment TextureFile NAME` header line, and the texture beside it. Faces no view saw have all-zero
// texture coordinates. Only for a single page (the format has no page index per face); tools that
// compare a baked texture with ground truth face by face read it.

#include <filesystem>

#include "lib/image/image_io.h"
#include "texturing/textured_mesh.h"

namespace lutex {

// Writes MODEL.ply and MODEL_texture.png (`page_encoding`: kSrgb8 or kLinear16). Throws
// std::runtime_error when the atlas has more than one page.
void WriteTexturedPly(const TexturedMesh& textured, const std::filesystem::path& path,
                      ImageEncoding page_encoding = ImageEncoding::kSrgb8);

}  // namespace lutex
