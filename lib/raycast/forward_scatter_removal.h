#pragma once

// Forward scattering (lib/model/forward_scatter.h) taken out of an image whose surfaces were ray-cast:
// the range of each pixel's surface comes from the ray-cast depth, the kernel's angles from the camera's
// focal length. Calibration (every image it samples known colours or correspondences from) and restoration
// call this with the forward scattering the LUT records, so both see the same signal.

#include <opencv2/core.hpp>

#include "lib/lut/frustum_lut.h"
#include "lib/model/forward_scatter.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

// The distance from the camera to each pixel's surface along its ray (planar depth / the ray's z),
// CV_32F, NaN where there is none. `maps` must cover the whole image of `rays`.
cv::Mat RangeAlongRays(const GeometryMaps& maps, const CameraRays& rays);

// The backscatter β of `lut` at each pixel's surface (at its planar depth), times `gain` (an image
// recorded with exposure gain g shows g β): CV_32FC3 the size of the maps, 0 where there is no surface.
// `maps` must cover the whole image of the LUT's grid.
cv::Mat BackscatterAtSurfaces(const FrustumLut& lut, const GeometryMaps& maps, double gain);

// `image` (linear CV_32FC3, the size of `rays`' camera) without the forward-scattered light of `scatter`;
// the image itself when `scatter` is none.
//
// Forward scattering spreads the light that left the surface; the backscatter, scattered from the beams
// into the camera, is smooth and is not spread again (to first order). With `backscatter` (an estimate
// of it per pixel, BackscatterAtSurfaces; empty: none) the correction is applied to the image minus the
// backscatter, which is then added back: inverting the whole image would also sharpen the backscatter's
// own gradients (in lutex's simulator, coastal water at 2 m: 1.5 % of the true radiance at the median and
// 8 % at the 99th percentile left wrong, against 0.2 % at worst with the backscatter taken out first).
//
// A pixel clipped in any channel (at or above `saturation_level` in the recorded image) keeps its
// recorded value, so that whoever samples or restores the result still sees it as clipped: its true
// radiance is unknown, and the correction would otherwise pull it below the level (and its neighbours'
// veil is then estimated from the clipped value, a little low).
cv::Mat WithoutForwardScatter(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                              const ForwardScatter& scatter, double saturation_level,
                              const cv::Mat& backscatter = cv::Mat());

}  // namespace lutex
