#pragma once

// Ray casting against a triangle mesh with Embree 3 (a high-quality, robust BVH). Embree's handles live
// behind the pimpl; no exception crosses its callbacks: device errors are recorded and thrown after the
// build. Geometry is shifted to a local origin (the centre of the mesh bounds) before it is converted
// to float, so georeferenced meshes keep their precision.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "lib/geometry/mesh.h"
#include "lib/geometry/rigid3d.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct RayHit {
  bool hit = false;
  double distance = 0.0;  // along the (unit) ray direction
  int face_id = -1;
  float b1 = 0.0f, b2 = 0.0f;  // hit point = (1 - b1 - b2) v0 + b1 v1 + b2 v2 of the face
  Eigen::Vector3d normal_in_world = Eigen::Vector3d::Zero();  // unit geometric normal, facing the ray origin
};

class RaycastScene {
 public:
  // Throws std::runtime_error when the mesh is invalid or Embree fails to build.
  explicit RaycastScene(const Mesh& mesh);
  ~RaycastScene();
  RaycastScene(const RaycastScene&) = delete;
  RaycastScene& operator=(const RaycastScene&) = delete;

  // Per-pixel maps of the image taken by `rays.camera()` at pose `cam_from_world`.
  GeometryMaps Render(const CameraRays& rays, const Rigid3d& cam_from_world,
                      const GeometryMapsOptions& options = {}) const;
  // The same into `maps`, reusing its buffers when they already have this size and type: a dive's images,
  // cast one after another into the same maps, take no fresh memory per image (at 12 MP the maps are
  // 240 MB, which the system would otherwise hand out, zeroed, for every image). Maps not requested
  // are released.
  void Render(const CameraRays& rays, const Rigid3d& cam_from_world, const GeometryMapsOptions& options,
              GeometryMaps* maps) const;

  // Planar depth z in the camera frame (as GeometryMaps::depth) of each of `pixels` of the image taken by
  // `rays.camera()` at `cam_from_world`, NaN where the ray hits nothing or the pixel is off the image.
  // For a few pixels scattered over an image (seam points), where rendering their rectangle would
  // render most of it: each pixel is cast (no adaptive fill), in packets of 16, on the calling thread.
  void CastDepths(const CameraRays& rays, const Rigid3d& cam_from_world, const std::vector<cv::Point>& pixels,
                  std::vector<float>* depths) const;

  // One ray in the world frame (direction need not be unit; the distance is in units of its length).
  RayHit Intersect(const Eigen::Vector3d& origin_in_world, const Eigen::Vector3d& direction_in_world) const;

  std::size_t NumFaces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lutex
