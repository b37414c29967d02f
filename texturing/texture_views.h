#pragma once

// The views a texture is baked from: each a posed camera and a way to load its pixels on demand, so the
// texturer never holds more than one image per worker thread, whatever the number of views.

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

struct TextureView {
  std::string name;  // for messages
  Camera camera;
  Rigid3d cam_from_world;
};

// Loads a view's pixels. Called from worker threads, at most one call per thread at a time.
struct ViewImageSource {
  // Linear RGB CV_32FC3 of the camera's size (restored albedo, or any linear image). Must throw naming
  // the file when it cannot be read or has the wrong size.
  std::function<cv::Mat(std::size_t view_index)> linear_rgb;
  // Per-channel confidence in [0, 1], CV_32FC3 of the camera's size, or an empty Mat when the view has
  // none (every pixel is then trusted). May be left unset: no view has confidence.
  std::function<cv::Mat(std::size_t view_index)> confidence;
};

// The view's image from `source`; throws naming the view when it is not CV_32FC3 of the camera's size.
cv::Mat LoadViewImage(const ViewImageSource& source, const std::vector<TextureView>& views, std::size_t view_index);

// The view's confidence, or an empty Mat when the source has none for it; throws naming the view when it
// is not CV_32FC3 of the camera's size.
cv::Mat LoadViewConfidence(const ViewImageSource& source, const std::vector<TextureView>& views,
                           std::size_t view_index);

// Ray casts views of one mesh. The ray table of each camera is built once, on first use, and shared by
// every view with the same camera id (a dive usually has one camera).
class ViewRaycaster {
 public:
  explicit ViewRaycaster(const RaycastScene& scene) : scene_(scene) {}

  // Depth and face id of every pixel of `view` into `maps`, or of the pixels of `window` when it is not
  // empty (maps.origin tells where the maps start), reusing its buffers (one set per worker: no fresh
  // memory per view). One thread: views run in parallel.
  void Render(const TextureView& view, GeometryMaps* maps, const cv::Rect& window = cv::Rect()) const;

 private:
  const CameraRays& RaysFor(const Camera& camera) const;

  const RaycastScene& scene_;
  mutable std::mutex mutex_;
  mutable std::map<std::uint32_t, std::unique_ptr<CameraRays>> rays_by_camera_;
};

}  // namespace lutex
