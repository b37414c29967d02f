#pragma once

// Viewers tested for real: a page served from a local folder on 127.0.0.1, rendered by headless Chromium
// (SwiftShader's software WebGL), and its screenshot checked.

#include <sys/types.h>

#include <array>
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace lutex::testing {

// Python's static file server on 127.0.0.1, on a port the system picks, serving `root` until destroyed.
// Its request log goes to `log`.
class LocalHttpServer {
 public:
  LocalHttpServer(const std::filesystem::path& root, const std::filesystem::path& log);
  ~LocalHttpServer();
  LocalHttpServer(const LocalHttpServer&) = delete;
  LocalHttpServer& operator=(const LocalHttpServer&) = delete;

  int port() const { return port_; }  // 0 when it did not start

 private:
  pid_t pid_ = 0;
  int port_ = 0;
};

// Opens `url` in headless Chromium with a `width` x `height` window and saves the screenshot, taken when
// the page's virtual time budget (10 s) has run out. Returns Chromium's log, the page's console included.
std::string TakeScreenshot(const std::string& url, const std::filesystem::path& screenshot, int width, int height);

// The share of `pixels` within `tolerance` of `expected` (RGB) in every channel; `pixels` is OpenCV's BGR.
double ShareNear(const cv::Mat& pixels, const cv::Vec3b& expected, int tolerance);

// Checks (gtest expectations) that the screenshot `picture` shows, on a black background, a rectangle of
// width / height `aspect` seen from straight above whose quadrants are north-west, north-east,
// south-west and south-east (`colours`, RGB, in that order) with north up and east right; returns the
// rectangle's bounds in the picture.
cv::Rect ExpectQuadrantsFromAbove(const cv::Mat& picture, double aspect, const std::array<cv::Vec3b, 4>& colours,
                                  const std::string& viewer);

}  // namespace lutex::testing
