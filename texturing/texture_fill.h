#pragma once

// Fills the texels of an atlas page that no view coloured (NaN): padding between charts and texels no
// view sees. Pull-push (Gortler et al. 1996, "The Lumigraph"): the page is averaged down a pyramid over
// known texels only, then every unknown texel takes the value of the coarsest level where its region
// had known texels, interpolated up level by level. Near a chart this continues the chart's own border
// colours, so bilinear filtering and mip-mapping across a chart's edge do not pull in other charts or
// black.

#include <opencv2/core.hpp>

namespace lutex {

// `page`: CV_32FC3, NaN = unknown. A page with no known texel becomes 0. Rows are filled on up to
// `num_threads` threads (<= 0: all cores); the result does not depend on how many.
void FillUnknownTexels(cv::Mat& page, int num_threads = 1);

}  // namespace lutex
