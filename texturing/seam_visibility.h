#pragma once

// How visible the seams of a texture are. For every mesh edge shared by two textured faces, the texture
// is sampled on both sides, each side through its own face's texture coordinates, at points one texel
// away from the edge (at a quarter, half and three quarters along it); the step is the mean absolute
// difference over channels, in linear albedo.
//
// Across a chart border (different pages or texture coordinates) the step is the seam plus the
// texture's own change over two texels (its detail and its noise); across an edge inside a chart it is
// only the latter. The seam's visibility is the difference of the two means.

#include "texturing/face_adjacency.h"
#include "texturing/textured_mesh.h"

namespace lutex {

struct SeamVisibility {
  std::size_t num_seam_edges = 0;
  double seam_step = 0.0;      // mean step across chart borders, linear albedo (0..1)
  double interior_step = 0.0;  // the same across edges inside charts
  double Excess() const { return seam_step - interior_step; }
};

SeamVisibility MeasureSeamVisibility(const TexturedMesh& textured, const FaceAdjacency& adjacency);

}  // namespace lutex
