#pragma once

// 8-bit pictures of geometry maps for people to look at (not for computation).

#include <opencv2/core.hpp>

namespace lutex {

// Depth (CV_32F, NaN = no hit) as a BGR turbo colour map from the image's nearest (blue) to farthest
// (red) hit; black where nothing is hit.
cv::Mat DepthPreview(const cv::Mat& depth);

// Normals (CV_32FC3, camera frame) as BGR with RGB = (n + 1) / 2 per axis; black where nothing is hit.
cv::Mat NormalPreview(const cv::Mat& normal);

}  // namespace lutex
