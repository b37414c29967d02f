#include "texturing/texture_views.h"

namespace lutex {

const CameraRays& ViewRaycaster::RaysFor(const Camera& camera) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::unique_ptr<CameraRays>& rays = rays_by_camera_[camera.camera_id];
  if (!rays) rays = std::make_unique<CameraRays>(camera, 1);
  return *rays;
}

GeometryMaps ViewRaycaster::Render(const TextureView& view) const {
  GeometryMapsOptions options;
  options.normal = true;
  options.face_id = true;
  options.num_threads = 1;
  return scene_.Render(RaysFor(view.camera), view.cam_from_world, options);
}

}  // namespace lutex
