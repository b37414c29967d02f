#include "lib/raycast/camera_rays.h"

#include <limits>

#include "lib/util/parallel_for.h"

namespace lutex {

CameraRays::CameraRays(const Camera& camera, int num_threads) : camera_(camera) {
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

}  // namespace lutex
