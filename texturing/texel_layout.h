#pragma once

// The texels of an atlas, each tied to the surface point it shows: the face and the barycentric
// coordinates of the texel centre in that face. A texel inside a chart's triangle shows the point under
// its centre; a texel of the chart's border (within `gutter` texels of a triangle, outside all of them)
// shows the nearest point of the nearest triangle, so bilinear filtering and the first mip levels at a
// chart's edge see surface colours, not the padding.
//
// Texels are ordered chart by chart, and within a chart face by face, so each face's texels are one
// contiguous range.

#include <cstdint>
#include <utility>
#include <vector>

#include "texturing/atlas_packing.h"
#include "texturing/texture_charts.h"

namespace lutex {

struct AtlasTexel {
  std::uint32_t face = 0;
  std::uint16_t page = 0;
  std::uint16_t x = 0;  // texel column and row in the page
  std::uint16_t y = 0;
  float b1 = 0.0f;  // surface point = (1 - b1 - b2) v0 + b1 v1 + b2 v2 of the face
  float b2 = 0.0f;
};

struct TexelLayout {
  std::vector<AtlasTexel> texels;
  // Texels of face f: [face_ranges[f].first, face_ranges[f].second); empty for untextured faces.
  std::vector<std::pair<std::size_t, std::size_t>> face_ranges;
  // Texels of chart c: [chart_offsets[c], chart_offsets[c + 1]).
  std::vector<std::size_t> chart_offsets;
};

// `num_faces` is the mesh's face count. Charts are rasterised in parallel (<= 0 threads: all cores);
// the result does not depend on the thread count.
TexelLayout RasterizeTexels(const std::vector<TextureChart>& charts, const AtlasLayout& layout, std::size_t num_faces,
                            double gutter, int num_threads);

// How many texels RasterizeTexels gives each chart (rasterised in parallel and dropped), so that an atlas
// can be cut into batches of a known texel count before any batch is laid out.
std::vector<std::size_t> CountChartTexels(const std::vector<TextureChart>& charts, double gutter, int num_threads);

// The same for the charts `chart_indices` only, in that order (chart_offsets count them in that order;
// the other charts' faces have empty ranges): an atlas laid out a batch of charts at a time, so that only
// one batch's texels are held.
TexelLayout RasterizeTexels(const std::vector<TextureChart>& charts, const AtlasLayout& layout,
                            const std::vector<std::size_t>& chart_indices, std::size_t num_faces, double gutter,
                            int num_threads);

}  // namespace lutex
