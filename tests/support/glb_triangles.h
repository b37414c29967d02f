#pragma once

// A GLB as lutex writes it (texturing/gltf_export.h), read back as a viewer would: every triangle in the
// model's frame (the root node's transform undone) and the texture's colour at its centroid.

#include <array>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace lutex::testing {

struct GlbImage {
  int width = 0, height = 0, components = 0;
  std::vector<unsigned char> pixels;  // 8-bit sRGB, row by row
};

struct GlbTriangles {
  std::vector<std::array<Eigen::Vector3d, 3>> corners_in_model;
  // Linear RGB, bilinear from the 8-bit sRGB texture at the centroid's texture coordinates; NaN for a
  // triangle without texture.
  std::vector<Eigen::Vector3d> centroid_albedo;
  // The vertices in the tiles frame of 3D Tiles (glTF's node transform, then +Y up turned to +Z up).
  std::vector<Eigen::Vector3d> vertices_in_tiles_frame;
  // Texture coordinates of each triangle's corners and its texture (-1: none).
  std::vector<std::array<Eigen::Vector2d, 3>> corner_uv;
  std::vector<int> triangle_image;
  std::vector<GlbImage> images;

  // The texture's colour at the point (1 - b1 - b2) c0 + b1 c1 + b2 c2 of `triangle`, as centroid_albedo.
  Eigen::Vector3d AlbedoAt(std::size_t triangle, double b1, double b2) const;
};

// Fails the calling test (and returns what it read) when the file cannot be read.
GlbTriangles ReadGlbTriangles(const std::filesystem::path& glb);

}  // namespace lutex::testing
