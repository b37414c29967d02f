#pragma once

// The per-channel confidence maps `lutex restore` writes beside its restored images and `lutex texture`
// reads: FOLDER/NAME with the extension replaced by .png, 8-bit RGB, 255 = confidence 1 (a plain
// fraction, stored linearly, not sRGB).

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "lib/geometry/camera.h"

namespace lutex {

// Where the confidence map of image `name` (as the model names it) lives in `folder`.
std::filesystem::path ConfidenceMapPath(const std::filesystem::path& folder, const std::string& name);

// Writes a CV_32FC3 RGB confidence in [0, 1] (temporary name, then rename).
void WriteConfidenceMap(const cv::Mat& confidence, const std::filesystem::path& path);

// Reads a confidence map as stored: 8-bit BGR, checked. Throws std::runtime_error naming the file when it
// cannot be read or is not the camera's size.
cv::Mat ReadEncodedConfidenceMap(const std::filesystem::path& path, const Camera& camera);

// CV_32FC3 RGB in [0, 1] of a stored map's pixels in `window` (within it), or of all of it when empty.
cv::Mat DecodeConfidenceMap(const cv::Mat& encoded, const cv::Rect& window = cv::Rect());

// The two in one: a confidence map read and decoded, as above.
cv::Mat ReadConfidenceMap(const std::filesystem::path& path, const Camera& camera, const cv::Rect& window = cv::Rect());

}  // namespace lutex
