#pragma once

// Atlas pages on disk. The default is what every viewer expects of a colour texture: 8-bit sRGB PNG.
// For measurement, 16-bit linear PNG keeps the albedo without the 8-bit quantisation (DESIGN.md:
// encodings are explicit).

#include <vector>

#include <opencv2/core.hpp>

#include "lib/image/image_io.h"

namespace lutex {

// PNG bytes of a linear RGB CV_32FC3 page in `encoding` (kSrgb8 or kLinear16).
std::vector<unsigned char> EncodeAtlasPage(const cv::Mat& page, ImageEncoding encoding = ImageEncoding::kSrgb8);

}  // namespace lutex
