#pragma once

// How lutex asks the C library's allocator to treat large blocks: `lutex tiles` sets it as it starts
// (colmap_integration/stages/tiles_workspace.cc), for the rest of the process.
//
// Streamed work (3D Tiles, the mosaic) allocates and frees buffers of the same few sizes tile after tile:
// a leaf's texels, decoded images, ray-cast maps, a few to tens of MB each. glibc's malloc maps a block
// of 128 KiB or more from the system and gives it back when freed, but each time such a block is freed it
// raises that threshold to the block's size (up to 32 MiB); from then on those blocks come from its heaps,
// and their freed space stays with the process, scattered between smaller live blocks where it cannot be
// returned. Over a whole dive the resident set of `lutex tiles` climbed to 1.5 times what one tile needs
// and then stayed there. A fixed threshold maps every block of at least `kLargeBlockBytes` from the system
// and returns it when freed, so the heaps keep only the small blocks.
//
// The threshold is a trade: below it, blocks are reused from the heaps without the system zeroing fresh
// pages for them. Measured on `lutex tiles` over a simulated dive of 5 M faces (197 tiles, 2 threads),
// peak and time: glibc's default 437 MiB in 144 s, 1 MiB 302 MiB in 210 s, 4 MiB 355 MiB in 156 s,
// 8 MiB 353 MiB in 151 s (README, "Speed and memory" under `lutex tiles`). The mosaic, which allocates
// its tiles' buffers of this size many times over, gave 4 % less memory for 24-43 % more time, so it, and
// every other command, keeps glibc's default.
//
// Elsewhere (not glibc, or under a sanitizer's allocator) this does nothing.

#include <cstddef>

namespace lutex {

inline constexpr std::size_t kLargeBlockBytes = std::size_t{4} << 20;

void MapLargeBlocksFromTheSystem();

}  // namespace lutex
