#pragma once

// Surface samples of one survey image for correspondence constraints (paper Sec. 2.2, "Correspondence
// Constraints"): SLIC superpixels (OpenCV contrib, SLICO variant), each reduced to one homogeneous sample.
// The paper takes a superpixel's centre; lutex takes its most interior pixel (farthest from the
// superpixel's border, so non-convex superpixels still give a point inside) and, as its colour, the
// per-channel median over its inner pixels (those at least a third of that depth inside), so edges and
// noise do not colour it. Dropped: superpixels with any inner pixel without geometry, whose inner depth
// spans more than `max_relative_depth_range` (a depth discontinuity), with saturated inner pixels, whose
// colour spread (median absolute deviation / median, green) exceeds `max_relative_color_spread`, or
// seen at a grazing angle.
//
// Large images are segmented at a working resolution of at most `working_width` pixels across (SLIC
// costs grow with pixels, and 300 superpixels do not need 12 MP); the samples' pixels and footprints are
// in the full image.

#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/model/shading.h"
#include "lib/calibration/observations.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct SuperpixelOptions {
  int count = 300;  // superpixels per image (paper: 300)
  // Wider images are segmented (and their samples' colours taken) at this width: SLIC's cost grows with
  // the pixels, while 300 superpixels of a 640-px-wide image still span ~30 px each, plenty to find
  // homogeneous patches. Footprints and points are mapped back to full resolution.
  int working_width = 640;
  double saturation_level = 0.98;
  double min_cos_theta = 0.3;
  double max_relative_depth_range = 0.03;
  double max_relative_color_spread = 0.15;
  // Where the light is taken to be for cos_theta (image_formation.h); must match the restoration's.
  Shading shading;

  void Check() const;
};

struct SurfaceSample {
  SurfaceView view;
  // Radius (full-image pixels) of the disk around view.pixel inside the superpixel: the footprint over
  // which other views sample the same surface.
  double footprint_radius = 1.0;
};

// `image`: linear RGB CV_32FC3 of the camera of `rays`; `maps`: its depth and normals.
std::vector<SurfaceSample> SampleSuperpixels(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays,
                                             const SuperpixelOptions& options = SuperpixelOptions());

}  // namespace lutex
