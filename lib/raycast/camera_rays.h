#pragma once

// Unit ray directions in the camera frame through every pixel centre of a camera. Unprojecting a
// distorted camera costs a Newton solve per pixel, so a dive (thousands of images, usually one camera)
// computes the table once per camera and reuses it for every pose. Memory: 12 bytes per pixel
// (144 MB for 12 MP).

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/camera.h"

namespace lutex {

// The pixel (column or row) of an image `size` pixels across whose ray a table strided by `stride` holds
// at `index`: the centre pixel of its block, stride index + stride / 2, clamped to the image.
inline int StridedPixel(int index, int stride, int size) { return std::min(stride * index + stride / 2, size - 1); }

class CameraRays {
 public:
  // Rays through pixel centres (col + 0.5, row + 0.5). Pixels whose ray cannot be represented (beyond
  // 90 degrees for fisheye models) get a NaN direction and never hit anything.
  CameraRays(const Camera& camera, int num_threads = 0);

  // A coarse table of `full` (a table of every pixel): one ray per `stride` x `stride` block of its
  // pixels, the ray of the block's pixel (StridedPixel(col), StridedPixel(row)), in a table of
  // ceil(width / stride) x ceil(height / stride). A ray cast with it visits every stride-th pixel in each
  // direction. camera() stays the full camera.
  static CameraRays Strided(const CameraRays& full, int stride);

  const Camera& camera() const { return camera_; }
  // The table's size (the camera's, but for a strided table).
  int width() const { return width_; }
  int height() const { return height_; }
  // Unit direction of the ray through the table's pixel (col, row), camera frame.
  const Eigen::Vector3f& Direction(int col, int row) const {
    return directions_[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(col)];
  }

 private:
  CameraRays() = default;

  Camera camera_;
  int width_ = 0, height_ = 0, stride_ = 1;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace lutex
