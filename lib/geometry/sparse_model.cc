#include "lib/geometry/sparse_model.h"

#include <stdexcept>

namespace lutex {

void SparseModel::Check(const std::string& context) const {
  CheckCameras(context);
  CheckImages(context);
  CheckPoints3D(context);
}

void SparseModel::CheckCameras(const std::string& context) const {
  for (const auto& [camera_id, camera] : cameras) {
    if (camera.camera_id != camera_id) {
      throw std::runtime_error(context + ": camera " + std::to_string(camera_id) + " is stored under another id");
    }
    camera.Check(context);
  }
}

void SparseModel::CheckImages(const std::string& context) const {
  for (const auto& [image_id, image] : images) {
    if (cameras.count(image.camera_id) == 0) {
      throw std::runtime_error(context + ": image " + std::to_string(image_id) + " ('" + image.name +
                               "') names camera " + std::to_string(image.camera_id) +
                               ", which the model does not define");
    }
    if (!image.cam_from_world.IsValid()) {
      throw std::runtime_error(context + ": image " + std::to_string(image_id) + " ('" + image.name +
                               "') has a pose that is not finite or a quaternion that is not unit");
    }
  }
}

void SparseModel::CheckPoints3D(const std::string& context) const {
  for (const auto& [point3D_id, point] : points3D) {
    if (!point.xyz.allFinite()) {
      throw std::runtime_error(context + ": 3-D point " + std::to_string(point3D_id) + " is not finite");
    }
    for (const TrackElement& element : point.track) {
      if (images.count(element.image_id) == 0) {
        throw std::runtime_error(context + ": 3-D point " + std::to_string(point3D_id) + " names image " +
                                 std::to_string(element.image_id) + ", which the model does not define");
      }
    }
  }
}

}  // namespace lutex
