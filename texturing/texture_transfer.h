#pragma once

// A coarser level's texture made from the finer textured surface it replaces (a tiled bake's parent from
// its children): no image is read again. Each texel of the coarse mesh shows the fine surface's texture
// where the line along the coarse face's normal, through the texel's surface point, meets the fine
// surface (the nearest such point within `search_distance` on either side). So a level shows the colours
// of the level below it, fused, levelled and with its views as they were chosen there, and a viewer that
// refines sees no change of colour, only of detail.
//
// The fine textures are handed over halved (HalveTexture): a coarse texel covers 2 x 2 fine texels, so
// the halving is the box filter the coarser sampling needs, and a parent holds a quarter of the texels of
// the children it is made from.

#include <cstdint>
#include <vector>

#include "lib/geometry/mesh.h"
#include "texturing/texture_baker.h"
#include "texturing/texture_views.h"
#include "texturing/textured_mesh.h"

namespace lutex {

// The same texture at half the resolution: each page averaged over 2 x 2 texels (a page of odd size is
// first extended by repeating its last column or row), the corner texels halved. Untextured faces stay so.
TexturedMesh HalveTexture(const TexturedMesh& textured);

// One textured part of the finer level, with the view each of its faces was textured from (kNoView:
// untextured).
struct TransferSource {
  const TexturedMesh* textured = nullptr;
  const std::vector<std::uint32_t>* view_of_face = nullptr;
};

struct TransferredTexture {
  TexturedMesh textured;  // its mesh is `coarse`
  // Per face of the coarse mesh: the view of the fine face under its centre (kNoView where no fine face
  // lies within the search distance); the charts are projected into it (texture_charts.h).
  std::vector<std::uint32_t> view_of_face;
};

// Bakes `coarse` at options.charts.texel_size from `fine` (`views`: what the labels index). Threads as
// options.num_threads; the result does not depend on them. Throws std::invalid_argument when a source has
// no texture or labels of another length, or search_distance is not positive.
TransferredTexture TransferTexture(const std::vector<TransferSource>& fine, const Mesh& coarse,
                                   const std::vector<TextureView>& views, double search_distance,
                                   const TextureBakingOptions& options);

}  // namespace lutex
