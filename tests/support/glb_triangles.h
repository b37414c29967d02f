#pragma once

// A GLB as lutex writes it (texturing/gltf_export.h), read back as a viewer would: every triangle in the
// model's frame (the root node's transform undone) and the texture's colour at its centroid.

#include <array>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace lutex::testing {

struct GlbTriangles {
  std::vector<std::array<Eigen::Vector3d, 3>> corners_in_model;
  // Linear RGB, bilinear from the 8-bit sRGB texture at the centroid's texture coordinates; NaN for a
  // triangle without texture.
  std::vector<Eigen::Vector3d> centroid_albedo;
  // The vertices in the tiles frame of 3D Tiles (glTF's node transform, then +Y up turned to +Z up).
  std::vector<Eigen::Vector3d> vertices_in_tiles_frame;
};

// Fails the calling test (and returns what it read) when the file cannot be read.
GlbTriangles ReadGlbTriangles(const std::filesystem::path& glb);

}  // namespace lutex::testing
