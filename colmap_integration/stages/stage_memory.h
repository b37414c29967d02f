#pragma once

// The memory check every image-by-image stage makes before its first image buffer is allocated
// (lib/util/memory_budget.h): what the loaded dive holds, the ray table of its largest camera, and what
// each worker holds for the image it is on. A camera of 20000 x 20000 pixels, or a few hundred workers, is refused
// with the estimate and the limit in one line, instead of being swapped to death or killed by the kernel.

#include <cstddef>
#include <string>

#include "colmap_integration/stages/loaded_dive.h"
#include "lib/util/memory_budget.h"
#include "texturing/texture_baker.h"

namespace lutex {

// Bytes a worker holds per pixel of the image it is on, by stage; each is a sum of the buffers named.
// Ray-cast maps: depth 4 + normal 12 + face id 4.
inline constexpr double kRaycastMapBytesPerPixel = 20.0;
// raycast: the maps, their COLMAP arrays as written (16) and 8-bit previews with their encoded copies (12).
inline constexpr double kRaycastStageBytesPerPixel = kRaycastMapBytesPerPixel + 16.0 + 12.0;
// restore, calibrate, texture, mosaic: the maps, the decoded image (up to 6), its linear float copy (12),
// the restored albedo and confidence (24) and their encoded copies (9).
inline constexpr double kImageStageBytesPerPixel = kRaycastMapBytesPerPixel + 6.0 + 12.0 + 24.0 + 9.0;

// Texture and mosaic, as an estimate's parts: the texel samples fusion may hold at once (texel_fusion.h),
// and the tables kept for every face of the mesh while it is baked (texture_baker.h): its view candidates,
// the view selection's data costs and messages, its neighbours, its view, its chart corners and texels.
MemoryEstimate TextureBakingMemory(const TextureBakingOptions& baking, std::size_t num_faces);

// Throws std::runtime_error "`stage` needs about X (parts), more than the memory limit of Y (...)" when
// the dive, the ray table of its largest camera, `num_threads` workers at `bytes_per_pixel` on the largest
// image, and `extra` exceed `limit_bytes` (0: the machine's available memory).
// `indexed_faces`: the faces whose ray-casting index the stage builds at once (0: the whole mesh's; `lutex
// tiles` builds one for each tile's piece, texturing/tile_views.h).
void CheckStageMemory(const std::string& stage, const LoadedDive& dive, int num_threads, double bytes_per_pixel,
                      std::size_t limit_bytes, MemoryEstimate extra = {}, std::size_t indexed_faces = 0);

}  // namespace lutex
