#pragma once

// Geometry compressed for glTF's EXT_meshopt_compression (Khronos extension registry): meshoptimizer's
// vertex codec for attribute streams (mode ATTRIBUTES) and its index codec for triangle lists (mode
// TRIANGLES), both format version 0, the one the extension specifies. Decoders (three.js with
// MeshoptDecoder, CesiumJS, Babylon.js, gltfpack) restore vertex streams byte for byte, so positions keep
// their float precision, and the same triangles with the same winding (the index codec may rotate a
// triangle's three indices).
//
// In the file, each compressed buffer view points into a "fallback" buffer that has a length but no data
// (the decoder fills it), and its extension object says where the compressed bytes are:
//   bufferViews[i] = {"buffer": FALLBACK, "byteOffset", "byteLength": count * stride, ["byteStride"],
//     "extensions": {"EXT_meshopt_compression": {"buffer": 0, "byteOffset", "byteLength", "byteStride",
//                                                "count", "mode": "ATTRIBUTES" | "TRIANGLES"}}}
//   buffers[FALLBACK] = {"byteLength", "extensions": {"EXT_meshopt_compression": {"fallback": true}}}
// and the extension is listed in extensionsRequired, since there is no uncompressed copy.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lutex {

// `count` elements of `stride` bytes each (a multiple of 4, at most 256, as the codec needs) from `data`.
// Throws std::invalid_argument for another stride.
std::vector<unsigned char> EncodeMeshoptAttributes(const void* data, std::size_t count, std::size_t stride);

// A triangle list (indices.size() a multiple of 3, each index below `vertex_count`); the decoder writes
// them as 16- or 32-bit indices, whichever the buffer view's stride says.
std::vector<unsigned char> EncodeMeshoptTriangles(const std::vector<std::uint32_t>& indices, std::size_t vertex_count);

}  // namespace lutex
