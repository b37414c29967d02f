#pragma once

// A mesh with an albedo texture atlas: what lutex texture produces and the exporters write.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lib/geo/georeference.h"
#include "lib/geometry/mesh.h"

namespace lutex {

struct TexturedMesh {
  // The input mesh, faces in their input order.
  Mesh mesh;
  // Atlas pages: linear RGB albedo, CV_32FC3, every texel filled.
  std::vector<cv::Mat> pages;
  // Page of each face, -1 for faces no view saw (exported without texture).
  std::vector<int> face_page;
  // Texel coordinates of each face's corners in its page: x right, y down, in texels (the centre of texel
  // (i, j) is (i + 0.5, j + 0.5)). Exporters divide by the page size and flip v as their format needs.
  std::vector<std::array<Eigen::Vector2f, 3>> face_corner_texels;
  // The model's up direction in the mesh's frame (unit). glTF is +Y up, so the glTF writer's root node
  // rotates this to +Y; the other formats have no convention and keep the mesh's frame.
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // Where the mesh's frame sits on the Earth (the glTF writer records it in asset.extras).
  Georeference georeference;

  std::size_t NumTexturedFaces() const;

  // The texture's colour at the surface point (1 - b1 - b2) v0 + b1 v1 + b2 v2 of `face`, bilinear as a
  // viewer samples it (without mip-mapping); NaN for an untextured face.
  Eigen::Vector3f AlbedoAt(std::uint32_t face, float b1, float b2) const;
};

}  // namespace lutex
