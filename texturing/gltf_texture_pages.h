#pragma once

// The texture pages of a glTF/GLB model, decoded, for pictures of a model (lutex report) and for tests.

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace lutex {

// Every image of the model as 8-bit BGR (alpha dropped), in the model's order. Throws std::runtime_error
// naming `path` when it cannot be read as glTF (binary by the .glb extension, else JSON).
std::vector<cv::Mat> ReadGltfTexturePages(const std::filesystem::path& path);

}  // namespace lutex
