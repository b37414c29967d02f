#pragma once

// Known-colour observations from one image: every `stride`-th pixel whose surface has a known albedo,
// skipping pixels that are saturated, seen at a grazing angle, or next to an albedo edge or a depth
// discontinuity (colour there mixes two surfaces; paper: homogeneous regions matter).

#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/model/shading.h"
#include "lib/calibration/observations.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct KnownColorSamplingOptions {
  int stride = 4;                  // pixels between samples, both directions
  double saturation_level = 0.98;  // linear values at or above this are clipped
  double min_cos_theta = 0.3;      // about 73 degrees
  int edge_margin = 2;             // pixels around a sample that must share its albedo and surface
  double max_relative_depth_step = 0.02;
  // Where the light is taken to be for cos_theta (image_formation.h); must match the restoration's.
  Shading shading;

  void Check() const;
};

// `image`: linear RGB CV_32FC3. `known_albedo`: linear RGB CV_32FC3, NaN where the albedo is unknown.
// `maps`: depth and normals of the same view.
std::vector<KnownColorObservation> SampleKnownColors(const cv::Mat& image, const cv::Mat& known_albedo,
                                                     const GeometryMaps& maps, const CameraRays& rays,
                                                     const KnownColorSamplingOptions& options = {});

}  // namespace lutex
