#include "lib/raycast/camera_rays.h"

#include <limits>
#include <stdexcept>
#include <string>

#include "lib/util/parallel_for.h"

namespace lutex {

CameraRays::CameraRays(const Camera& camera, int num_threads)
    : camera_(camera), width_(static_cast<int>(camera.width)), height_(static_cast<int>(camera.height)) {
  camera_.Check("camera " + std::to_string(camera.camera_id));
  directions_.resize(camera_.width * camera_.height);
  ParallelFor(camera_.height, num_threads, [&](std::size_t row) {
    for (std::size_t col = 0; col < camera_.width; ++col) {
      const Eigen::Vector3d ray = camera_.CamFromImg(
          Eigen::Vector2d(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5));
      directions_[row * camera_.width + col] =
          ray.allFinite() ? Eigen::Vector3f(ray.normalized().cast<float>())
                          : Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
    }
  });
}

CameraRays CameraRays::Strided(const CameraRays& full, int stride) {
  if (stride < 1 || full.stride_ != 1) {
    throw std::invalid_argument("a strided ray table needs a stride of at least 1 (got " + std::to_string(stride) +
                                ") over a table of every pixel");
  }
  CameraRays strided;
  strided.camera_ = full.camera_;
  strided.stride_ = stride;
  strided.width_ = (full.width_ + stride - 1) / stride;
  strided.height_ = (full.height_ + stride - 1) / stride;
  strided.directions_.reserve(static_cast<std::size_t>(strided.width_) * static_cast<std::size_t>(strided.height_));
  for (int row = 0; row < strided.height_; ++row) {
    for (int col = 0; col < strided.width_; ++col) {
      strided.directions_.push_back(
          full.Direction(StridedPixel(col, stride, full.width_), StridedPixel(row, stride, full.height_)));
    }
  }
  return strided;
}

}  // namespace lutex
