#pragma once

// A COLMAP sparse reconstruction as lutex holds it: cameras, registered images with their poses
// (cam_from_world) and 2-D points, and 3-D points with tracks. Field meanings follow COLMAP's formats.

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"

namespace lutex {

// The two encodings COLMAP stores a model in (files cameras/images/points3D .bin or .txt); the readers and
// writers are in colmap_integration/io/sparse_model_io.h.
enum class SparseFormat { kBinary, kText };

constexpr std::uint64_t kInvalidPoint3DId = std::numeric_limits<std::uint64_t>::max();

struct Point2D {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // pixel, centre of the top-left pixel at (0.5, 0.5)
  std::uint64_t point3D_id = kInvalidPoint3DId;
};

struct Image {
  std::uint32_t image_id = 0;
  std::uint32_t camera_id = 0;
  std::string name;  // path relative to the workspace's image folder
  Rigid3d cam_from_world;
  std::vector<Point2D> points2D;
};

struct TrackElement {
  std::uint32_t image_id = 0;
  std::uint32_t point2D_idx = 0;
};

struct Point3D {
  std::uint64_t point3D_id = 0;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Matrix<std::uint8_t, 3, 1> color = Eigen::Matrix<std::uint8_t, 3, 1>::Zero();
  double error = 0.0;
  std::vector<TrackElement> track;
};

struct SparseModel {
  std::map<std::uint32_t, Camera> cameras;
  std::map<std::uint32_t, Image> images;
  std::map<std::uint64_t, Point3D> points3D;

  // Throws std::runtime_error starting with `context` when a camera is invalid for its model, an image
  // names an undefined camera, a pose is not finite, or a track names an undefined image.
  void Check(const std::string& context) const;
  // The same for one kind of record, so a reader can name the file that holds the fault: the cameras
  // alone; the images (and the cameras they name); the 3-D points (and the images their tracks name).
  void CheckCameras(const std::string& context) const;
  void CheckImages(const std::string& context) const;
  void CheckPoints3D(const std::string& context) const;
};

}  // namespace lutex
