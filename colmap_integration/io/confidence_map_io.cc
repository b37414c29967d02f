#include "colmap_integration/io/confidence_map_io.h"

#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lib/image/image_io.h"

namespace lutex {

namespace fs = std::filesystem;

fs::path ConfidenceMapPath(const fs::path& folder, const std::string& name) {
  fs::path path = folder / name;
  path.replace_extension(".png");
  return path;
}

void WriteConfidenceMap(const cv::Mat& confidence, const fs::path& path) {
  // To 8 bits first, then swap channels: no float copy (144 MB of fresh memory per 12 MP image).
  cv::Mat confidence_8bit, confidence_bgr;
  confidence.convertTo(confidence_8bit, CV_8UC3, 255.0);
  cv::cvtColor(confidence_8bit, confidence_bgr, cv::COLOR_RGB2BGR);
  WriteEncodedImage(confidence_bgr, path);
}

cv::Mat ReadEncodedConfidenceMap(const fs::path& path, const Camera& camera) {
  const cv::Mat encoded = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (encoded.empty()) throw std::runtime_error(path.string() + ": cannot read the confidence map");
  if (encoded.cols != static_cast<int>(camera.width) || encoded.rows != static_cast<int>(camera.height)) {
    throw std::runtime_error(path.string() + ": the confidence map is " + std::to_string(encoded.cols) + "x" +
                             std::to_string(encoded.rows) + " but its camera is " + std::to_string(camera.width) +
                             "x" + std::to_string(camera.height));
  }
  return encoded;
}

cv::Mat DecodeConfidenceMap(const cv::Mat& encoded, const cv::Rect& window) {
  cv::Mat rgb;
  cv::cvtColor(window.empty() ? encoded : encoded(window), rgb, cv::COLOR_BGR2RGB);
  rgb.convertTo(rgb, CV_32FC3, 1.0 / 255.0);
  return rgb;
}

cv::Mat ReadConfidenceMap(const fs::path& path, const Camera& camera, const cv::Rect& window) {
  return DecodeConfidenceMap(ReadEncodedConfidenceMap(path, camera), window);
}

}  // namespace lutex
