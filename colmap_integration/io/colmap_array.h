#pragma once

// COLMAP's dense array format, used for depth maps and normal maps (stereo/depth_maps/*.bin,
// stereo/normal_maps/*.bin): an ASCII header "WIDTH&HEIGHT&CHANNELS&" followed directly by
// WIDTH*HEIGHT*CHANNELS little-endian float32 values, planar (all of channel 0, then channel 1, ...),
// each plane row-major. In memory lutex uses cv::Mat of CV_32FC(CHANNELS), channels interleaved.
//
// Invalid depth: COLMAP marks pixels without depth by 0, lutex by NaN. Files written for COLMAP tools
// should use 0 (see ReplaceNanWithZero); the reader returns values as stored.
//
// Pixel convention: lutex's depth of pixel (col, row) is measured along the ray through its centre
// (col + 0.5, row + 0.5). COLMAP 3.8's stereo_fusion back-projects pixel (col, row) through (col, row), so
// points it fuses from any depth map sit half a pixel off; that is COLMAP's convention, not an error here.

#include <filesystem>
#include <istream>
#include <ostream>

#include <opencv2/core.hpp>

namespace lutex {

cv::Mat ReadColmapArray(std::istream& stream);
cv::Mat ReadColmapArray(const std::filesystem::path& path);

// `array` must be CV_32F with 1 to 4 channels.
void WriteColmapArray(const cv::Mat& array, std::ostream& stream);
void WriteColmapArray(const cv::Mat& array, const std::filesystem::path& path);

// A copy with every NaN replaced by 0 (COLMAP's "no depth").
cv::Mat ReplaceNanWithZero(const cv::Mat& array);

}  // namespace lutex
