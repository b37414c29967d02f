#pragma once

// The albedo entries of the known-colour files (targets.h, chessboard_target.h, charuco_target.h):
// `<prefix>_linear`, three values in [0, 1], or `<prefix>_srgb8`, three values in [0, 255] (fractions
// allowed) decoded to linear. For the readers' .cc files only: it speaks nlohmann::json.

#include <string>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

namespace lutex {

// Throws std::runtime_error naming the key when neither is present, or it has not 3 numbers, or one is out
// of range.
Eigen::Vector3d ReadAlbedo(const nlohmann::json& object, const std::string& prefix);

}  // namespace lutex
