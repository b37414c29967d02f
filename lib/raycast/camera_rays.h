#pragma once

// Unit ray directions in the camera frame through every pixel centre of a camera. Unprojecting a
// distorted camera costs a Newton solve per pixel, so a dive (thousands of images, usually one camera)
// computes the table once per camera and reuses it for every pose. Memory: 12 bytes per pixel
// (144 MB for 12 MP).

#include <vector>

#include <Eigen/Core>

#include "lib/geometry/camera.h"

namespace lutex {

class CameraRays {
 public:
  // Rays through pixel centres (col + 0.5, row + 0.5). Pixels whose ray cannot be represented (beyond
  // 90 degrees for fisheye models) get a NaN direction and never hit anything.
  CameraRays(const Camera& camera, int num_threads = 0);

  const Camera& camera() const { return camera_; }
  int width() const { return static_cast<int>(camera_.width); }
  int height() const { return static_cast<int>(camera_.height); }
  // Unit direction of the ray through pixel (col, row), camera frame.
  const Eigen::Vector3f& Direction(int col, int row) const {
    return directions_[static_cast<std::size_t>(row) * camera_.width + col];
  }

 private:
  Camera camera_;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace lutex
