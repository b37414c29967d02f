#include "texturing/texture_views.h"

#include <stdexcept>
#include <string>

namespace lutex {

namespace {

void CheckViewPixels(const cv::Mat& pixels, const TextureView& view, const cv::Rect& window, const char* what) {
  const cv::Size size =
      window.empty() ? cv::Size(static_cast<int>(view.camera.width), static_cast<int>(view.camera.height)) : window.size();
  if (pixels.size() != size || pixels.type() != CV_32FC3) {
    throw std::runtime_error(view.name + ": the " + what + " is " + std::to_string(pixels.cols) + "x" +
                             std::to_string(pixels.rows) + (window.empty() ? " but the camera is " : " but the window is ") +
                             std::to_string(size.width) + "x" + std::to_string(size.height));
  }
}

}  // namespace

cv::Mat ViewWindow(const cv::Mat& image, const cv::Rect& window) {
  return window.empty() ? image.clone() : image(window).clone();
}

cv::Mat LoadViewImage(const ViewImageSource& source, const std::vector<TextureView>& views, std::size_t view_index,
                      const cv::Rect& window) {
  cv::Mat image = source.linear_rgb(view_index, window);
  CheckViewPixels(image, views[view_index], window, "image");
  return image;
}

cv::Mat LoadViewConfidence(const ViewImageSource& source, const std::vector<TextureView>& views,
                           std::size_t view_index, const cv::Rect& window) {
  cv::Mat confidence = source.confidence ? source.confidence(view_index, window) : cv::Mat();
  if (!confidence.empty()) CheckViewPixels(confidence, views[view_index], window, "confidence map");
  return confidence;
}

const CameraRays& ViewRaycaster::RaysFor(const Camera& camera, int stride) const {
  std::lock_guard<std::mutex> lock(rays_->mutex);
  std::unique_ptr<CameraRays>& full = rays_->by_camera[{camera.camera_id, 1}];
  if (!full) full = std::make_unique<CameraRays>(camera, 1);
  if (stride == 1) return *full;
  std::unique_ptr<CameraRays>& strided = rays_->by_camera[{camera.camera_id, stride}];
  if (!strided) strided = std::make_unique<CameraRays>(CameraRays::Strided(*full, stride));
  return *strided;
}

namespace {

// Depth and face id of the pixels of `window` (all when empty), on the calling thread.
GeometryMapsOptions DepthAndFaceIds(const cv::Rect& window) {
  GeometryMapsOptions options;
  options.normal = false;
  options.num_threads = 1;
  options.window = window;
  return options;
}

}  // namespace

void ViewRaycaster::Render(const TextureView& view, GeometryMaps* maps, const cv::Rect& window) const {
  scene_.Render(RaysFor(view.camera), view.cam_from_world, DepthAndFaceIds(window), maps);
}

void ViewRaycaster::RenderStrided(const TextureView& view, int stride, GeometryMaps* maps, const cv::Rect& window) const {
  scene_.Render(RaysFor(view.camera, stride), view.cam_from_world, DepthAndFaceIds(window), maps);
}

void ViewRaycaster::CastDepths(const TextureView& view, const std::vector<cv::Point>& pixels,
                               std::vector<float>* depths) const {
  scene_.CastDepths(RaysFor(view.camera), view.cam_from_world, pixels, depths);
}

}  // namespace lutex
