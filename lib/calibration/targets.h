#pragma once

// Known-colour targets: planar polygons of known albedo in the world frame of the COLMAP model (paper
// Sec. 4, colour boards). A targets file is JSON:
//
//   {"targets": [{"name": "orange board", "albedo_srgb8": [181, 110, 30],
//                 "corners_world": [[-2, 0, 1.5], [2, 0, 1.5], [2, 0, -1.5], [-2, 0, -1.5]]}, ...]}
//
// "albedo_srgb8" holds 8-bit sRGB values in [0, 255] (fractions allowed); give "albedo_linear": [r, g, b]
// in [0, 1] instead if the albedo is known linearly ("id" may stand for "name"). Corners go around the
// polygon (3 or more, coplanar to 1 mm). Other keys are ignored and entries without corners_world are
// skipped with a warning, so a file may describe more than the planar targets (the shared Blender
// datasets' metadata.json is a valid targets file).

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/geometry/rigid3d.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct Target {
  std::string name;
  Eigen::Vector3d albedo = Eigen::Vector3d::Zero();  // linear
  std::vector<Eigen::Vector3d> corners_world;

  // True when `point_in_world` lies on the target's plane (within `tolerance` metres) inside its polygon.
  bool Contains(const Eigen::Vector3d& point_in_world, double tolerance) const;
};

// Throws std::runtime_error naming the file and the target on a missing or malformed entry, an albedo out
// of range, or a non-planar or degenerate polygon.
std::vector<Target> ReadTargets(const std::filesystem::path& path);

// Per pixel, the albedo of the target the pixel's surface point lies on (CV_32FC3 linear RGB), NaN where
// none. The tolerance is 0.5 % of the depth plus 2 mm (the mesh of a target may be slightly off its
// nominal plane).
cv::Mat KnownAlbedoImage(const std::vector<Target>& targets, const GeometryMaps& maps, const CameraRays& rays,
                         const Rigid3d& cam_from_world);

}  // namespace lutex
