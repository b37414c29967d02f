#pragma once

// The albedo entries of the board files (chessboard_target.h, charuco_target.h): `<prefix>_linear`, three
// values in [0, 1], or `<prefix>_srgb8`, three values in [0, 255] decoded to linear. For the readers'
// .cc files only: it speaks nlohmann::json.

#include <string>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

namespace lutex {

// Throws std::runtime_error naming the key when it is missing, has not 3 values, or is out of range.
Eigen::Vector3d ReadBoardAlbedo(const nlohmann::json& object, const std::string& prefix);

}  // namespace lutex
