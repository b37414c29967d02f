#include "texturing/gltf_frame.h"

namespace lutex {

Eigen::Quaterniond GltfFromModel(const Eigen::Vector3d& up_in_model) {
  return Eigen::Quaterniond::FromTwoVectors(up_in_model.normalized(), Eigen::Vector3d::UnitY());
}

Eigen::Matrix3d TilesFromGltf() {
  Eigen::Matrix3d tiles_from_gltf;
  tiles_from_gltf << 1, 0, 0,  //
      0, 0, -1,                //
      0, 1, 0;
  return tiles_from_gltf;
}

Eigen::Matrix3d TilesFromModel(const Eigen::Vector3d& up_in_model) {
  return TilesFromGltf() * GltfFromModel(up_in_model).toRotationMatrix();
}

}  // namespace lutex
