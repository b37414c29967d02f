#pragma once

// Pictures of a LUT for people: for every slab, its alpha and its beta as 8-bit RGB images (bilinear
// between nodes, `width` pixels wide, the image's aspect ratio). Each quantity is scaled by its maximum
// over the whole LUT and channel-wise max, so slabs can be compared by eye; the scale is returned.

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "lib/lut/frustum_lut.h"

namespace lutex {

struct LutSlabImages {
  std::vector<cv::Mat> alpha;  // per slab, CV_8UC3 BGR
  std::vector<cv::Mat> beta;
  double alpha_scale = 0.0;    // linear value that maps to 255
  double beta_scale = 0.0;
};

LutSlabImages RenderLutSlabs(const FrustumLut& lut, int width = 320);

// Writes slab_KK_alpha.png and slab_KK_beta.png into `folder`.
void WriteLutSlabImages(const FrustumLut& lut, const std::filesystem::path& folder, int width = 320);

}  // namespace lutex
