#pragma once

// The other half of a correspondence: a surface sample of one image (superpixel_samples.h) looked up in
// another image of the survey. The sample's 3-D point is projected into the other image; it counts as
// seen there when it lands inside the image (with its footprint), in front of the camera, on the surface
// that image's depth map shows at that pixel (depth test: no occlusion), not at a grazing angle, and the
// footprint there is one surface (no depth step) of one colour (spread test) without clipped pixels. Its
// colour is the per-channel median over a footprint of the same size on the surface as the sample's.

#include <optional>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/model/shading.h"
#include "lib/calibration/observations.h"
#include "lib/geometry/rigid3d.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct CorrespondenceViewOptions {
  double max_relative_depth_difference = 0.01;  // the depth test, relative to the depth
  double saturation_level = 0.98;
  double min_cos_theta = 0.3;
  double max_relative_color_spread = 0.15;
  int max_footprint_pixels = 256;  // the footprint is subsampled beyond this
  Shading shading;

  void Check() const;
};

// One image with what a correspondence needs of it.
struct ViewedImage {
  const cv::Mat& image;  // linear RGB CV_32FC3
  const GeometryMaps& maps;
  const CameraRays& rays;
  const Rigid3d& cam_from_world;
};

// The view of `point_in_world`, whose footprint on the surface has radius `footprint_radius_world`
// (scene units), in `other`; nothing when it is not seen there (see above).
std::optional<SurfaceView> ViewInOtherImage(const Eigen::Vector3d& point_in_world, double footprint_radius_world,
                                            const ViewedImage& other,
                                            const CorrespondenceViewOptions& options = CorrespondenceViewOptions());

}  // namespace lutex
