#pragma once

// A textured model rendered back into every camera of a Blender dataset (lutex's ray caster and the
// texture lookup a viewer does) and compared with gt/albedo, the albedo seen through each pixel.

#include <filesystem>

#include "texturing/textured_mesh.h"

namespace lutex::testing {

// A textured PLY as lutex texture writes it (per-corner texcoords, v up; one 16-bit linear page
// NAME_texture.png beside it).
TexturedMesh ReadTexturedPly(const std::filesystem::path& ply);

struct RenderBack {
  double mae = 0.0;            // percentage points, over textured pixels and channels
  double textured_pixels = 0;  // fraction of surface pixels whose face is textured
};

// `dataset` is a Blender dataset folder (sparse/0 with the true poses, gt/albedo/*.exr).
RenderBack CompareWithGroundTruth(const std::filesystem::path& dataset, const TexturedMesh& textured);

}  // namespace lutex::testing
