#pragma once

// Forward scattering (lib/model/forward_scatter.h) taken out of an image whose surfaces were ray-cast:
// the range of each pixel's surface comes from the ray-cast depth, the kernel's angles from the camera's
// focal length. Calibration (every image it samples known colours or correspondences from) and restoration
// call this with the forward scattering the LUT records, so both see the same signal.

#include <opencv2/core.hpp>

#include "lib/model/forward_scatter.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

// The distance from the camera to each pixel's surface along its ray (planar depth / the ray's z),
// CV_32F, NaN where there is none. `maps` must cover the whole image of `rays`.
cv::Mat RangeAlongRays(const GeometryMaps& maps, const CameraRays& rays);

// `image` (linear CV_32FC3, the size of `rays`' camera) without the forward-scattered light of `scatter`;
// the image itself when `scatter` is none.
cv::Mat WithoutForwardScatter(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                              const ForwardScatter& scatter);

}  // namespace lutex
