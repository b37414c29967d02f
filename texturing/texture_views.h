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

// Loads a view's pixels, or the pixels of a window of the view (a texturer that samples a few faces of
// a 12 MP view needs their rectangle, not the image). Called from worker threads, at most one call per
// thread at a time. `window` lies within the image; an empty window is the whole image.
struct ViewImageSource {
  // Linear RGB CV_32FC3 of the window's size (restored albedo, or any linear image). Must throw naming
  // the file when it cannot be read or has the wrong size.
  std::function<cv::Mat(std::size_t view_index, const cv::Rect& window)> linear_rgb;
  // Per-channel confidence in [0, 1], CV_32FC3 of the window's size, or an empty Mat when the view has
  // none (every pixel is then trusted). May be left unset: no view has confidence.
  std::function<cv::Mat(std::size_t view_index, const cv::Rect& window)> confidence;
  // Whether the view's pixels are held in memory now, so that reading it is cheap (a cache): the fusion
  // reads those first, before a read of another view can drop them. May be left unset: none is.
  std::function<bool(std::size_t view_index)> is_held;
};

// The pixels of `window` of an image held in memory (a copy; the whole image for an empty window): what
// a ViewImageSource over images in memory returns.
cv::Mat ViewWindow(const cv::Mat& image, const cv::Rect& window);

// The view's image (or window of it) from `source`; throws naming the view when it is not CV_32FC3 of
// the window's size (the camera's for an empty window).
cv::Mat LoadViewImage(const ViewImageSource& source, const std::vector<TextureView>& views, std::size_t view_index,
                      const cv::Rect& window = cv::Rect());

// The view's confidence (or window of it), or an empty Mat when the source has none for it; throws naming
// the view when it is not CV_32FC3 of the window's size.
cv::Mat LoadViewConfidence(const ViewImageSource& source, const std::vector<TextureView>& views,
                           std::size_t view_index, const cv::Rect& window = cv::Rect());

// The ray tables of cameras, by camera id and stride, built on first use: at 12 MP a table is 144 MB and
// takes a fraction of a second, so raycasters of several meshes (the pieces of a tiled bake:
// tile_views.h) share them.
struct ViewRayTables {
  std::mutex mutex;
  std::map<std::pair<std::uint32_t, int>, std::unique_ptr<CameraRays>> by_camera;
};

// Ray casts views of one mesh. The ray table of each camera is built once, on first use, and shared by
// every view with the same camera id (a dive usually has one camera).
class ViewRaycaster {
 public:
  explicit ViewRaycaster(const RaycastScene& scene, std::shared_ptr<ViewRayTables> rays = std::make_shared<ViewRayTables>())
      : scene_(scene), rays_(std::move(rays)) {}

  // Depth and face id of every pixel of `view` into `maps`, or of the pixels of `window` when it is not
  // empty (maps.origin tells where the maps start), reusing its buffers (one set per worker: no fresh
  // memory per view). One thread: views run in parallel.
  void Render(const TextureView& view, GeometryMaps* maps, const cv::Rect& window = cv::Rect()) const;

  // Depth and face id of every `stride`-th pixel of `view` in each direction (CameraRays::Strided: maps
  // of ceil(width / stride) x ceil(height / stride)). `stride` 1 is Render's whole view.
  // `window` (in the strided table's pixels; empty: all) as for Render.
  void RenderStrided(const TextureView& view, int stride, GeometryMaps* maps, const cv::Rect& window = cv::Rect()) const;

  // Depth of each of `pixels` of `view` (RaycastScene::CastDepths), into `depths`. One thread.
  void CastDepths(const TextureView& view, const std::vector<cv::Point>& pixels, std::vector<float>* depths) const;

 private:
  const CameraRays& RaysFor(const Camera& camera, int stride = 1) const;

  const RaycastScene& scene_;
  std::shared_ptr<ViewRayTables> rays_;
};

}  // namespace lutex
