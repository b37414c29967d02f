#pragma once

// The frames a model is written in, in one place.
//
//   model     the mesh's own frame, whose up is TexturedMesh::up (for a georeferenced model +Z: east, north,
//             up)
//   glTF      +Y up, +Z forward (glTF 2.0, section 3.4): the GLB's root node rotates the model by the
//             smallest rotation taking its up to +Y; for a +Z-up model, -90 degrees about x, so north (+Y)
//             goes to glTF's -Z
//   tiles     3D Tiles is +Z up: a runtime turns glTF content by +90 degrees about x, (x, y, z) ->
//             (x, -z, y) (3D Tiles 1.1, "glTF transforms"), before the tile transforms. For a +Z-up
//             model the two rotations cancel: tile coordinates are model coordinates.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lutex {

// The root node's rotation: the model's up (need not be unit) to glTF's +Y.
Eigen::Quaterniond GltfFromModel(const Eigen::Vector3d& up_in_model);

// 3D Tiles' turn of glTF content to +Z up.
Eigen::Matrix3d TilesFromGltf();

// Both: the frame a tileset's bounding volumes and transforms speak of.
Eigen::Matrix3d TilesFromModel(const Eigen::Vector3d& up_in_model);

}  // namespace lutex
