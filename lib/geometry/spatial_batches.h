#pragma once

// Batches of items that lie close together: items (charts, tiles of a grid, ...) are taken in the order
// of a Morton (Z-order) curve through their points in `bounds` (10 bits per axis) and cut into batches
// of at most `max_size_per_batch` (an item larger than that is a batch of its own). A batch then covers
// one part of the space, so work done per batch touches only what lies near that part (the images that
// see it, the part of each image that shows it).
//
// When everything fits in one batch, the batch holds every item in index order. Otherwise the order
// along the curve breaks ties by index, so batches do not depend on anything but the inputs.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lutex {

// `points[i]` and `sizes[i]`: item i's place and size (texels, bytes, ...). Items of size 0 are kept.
std::vector<std::vector<std::size_t>> BatchAlongMortonCurve(const std::vector<Eigen::Vector3d>& points,
                                                            const std::vector<std::size_t>& sizes,
                                                            const Eigen::AlignedBox3d& bounds,
                                                            std::size_t max_size_per_batch);

}  // namespace lutex
