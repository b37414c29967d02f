#include "tests/support/headless_browser.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "tests/support/run_command.h"

namespace lutex::testing {

namespace fs = std::filesystem;

LocalHttpServer::LocalHttpServer(const fs::path& root, const fs::path& log) {
  const std::string script =
      "import functools, http.server, sys\n"
      "handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=sys.argv[1])\n"
      "server = http.server.ThreadingHTTPServer(('127.0.0.1', 0), handler)\n"
      "print(server.server_address[1], flush=True)\n"
      "server.serve_forever()\n";
  std::vector<std::string> arguments = {"python3", "-c", script, root.string()};
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 1);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = 0;
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  // The first line is the port; end of file (the server died) leaves port_ at 0.
  FILE* output = fdopen(pipe_ends[0], "r");
  std::array<char, 32> line{};
  if (pid_ != 0 && fgets(line.data(), int(line.size()), output)) port_ = std::atoi(line.data());
  fclose(output);
}

LocalHttpServer::~LocalHttpServer() {
  if (pid_ == 0) return;
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
}

std::string TakeScreenshot(const std::string& url, const fs::path& screenshot, int width, int height) {
  // SwiftShader (software WebGL): headless Chromium has no GPU. The virtual time budget lets the page load
  // and draw before the screenshot is taken; the window takes its full --window-size only then (the
  // viewers' pages draw again on the resize). The page's console comes out in Chromium's log.
  // On a loaded machine Chromium has been seen to hang past the budget (killed at 90 s, no screenshot,
  // while the same page rendered in 14 s alone): one more try then. A page that renders wrongly still
  // fails, since the screenshot is checked.
  const std::string command =
      "timeout 90 chromium --headless --no-sandbox --disable-dev-shm-usage --disable-background-networking "
      "--no-first-run --hide-scrollbars --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--run-all-compositor-stages-before-draw --virtual-time-budget=10000 --enable-logging=stderr --v=0 "
      "--window-size=" + std::to_string(width) + "," + std::to_string(height) +
      " --screenshot=" + screenshot.string() + " '" + url + "'";
  CommandResult result = RunCommand(command);
  if (result.exit_code == 124 && !fs::exists(screenshot)) {
    const std::string first = result.output;
    result = RunCommand(command);
    result.output = "first try timed out:\n" + first + "\nsecond try:\n" + result.output;
  }
  return result.output;
}

double ShareNear(const cv::Mat& pixels, const cv::Vec3b& expected, int tolerance) {
  int near = 0;
  for (int row = 0; row < pixels.rows; ++row) {
    for (int col = 0; col < pixels.cols; ++col) {
      const cv::Vec3b bgr = pixels.at<cv::Vec3b>(row, col);
      near += std::abs(bgr[2] - expected[0]) <= tolerance && std::abs(bgr[1] - expected[1]) <= tolerance &&
              std::abs(bgr[0] - expected[2]) <= tolerance;
    }
  }
  return double(near) / double(pixels.total());
}

cv::Rect ExpectQuadrantsFromAbove(const cv::Mat& picture, double aspect, const std::array<cv::Vec3b, 4>& colours,
                                  const std::string& viewer) {
  // The model: whatever is not the black background.
  cv::Mat model_mask;
  cv::inRange(picture, cv::Scalar(0, 0, 0), cv::Scalar(30, 30, 30), model_mask);
  cv::bitwise_not(model_mask, model_mask);
  const double covered = double(cv::countNonZero(model_mask)) / double(picture.total());
  std::vector<cv::Point> model_pixels;
  cv::findNonZero(model_mask, model_pixels);
  if (model_pixels.empty()) {
    ADD_FAILURE() << "the screenshot is black";
    return {};
  }
  const cv::Rect bounds = cv::boundingRect(model_pixels);
  std::cout << viewer << " render: the model covers " << 100.0 * covered << " % of the window, bounds " << bounds.width
            << " x " << bounds.height << " px at (" << bounds.x << ", " << bounds.y << ")\n";
  EXPECT_GT(covered, 0.2);
  EXPECT_NEAR(double(bounds.width) / double(bounds.height), aspect, 0.1) << "not seen from straight above";
  EXPECT_GT(double(cv::countNonZero(model_mask(bounds))) / double(bounds.area()), 0.95) << "not a rectangle";

  // Each quadrant of the bounds in its colour: north up, east right, not mirrored.
  const int half_width = bounds.width / 2, half_height = bounds.height / 2;
  const char* names[] = {"north-west (top left)", "north-east (top right)", "south-west (bottom left)",
                         "south-east (bottom right)"};
  for (int q = 0; q < 4; ++q) {
    const cv::Rect quadrant(bounds.x + ((q & 1) ? half_width : 0), bounds.y + ((q & 2) ? half_height : 0), half_width,
                            half_height);
    const double share = ShareNear(picture(quadrant), colours[q], 40);
    std::cout << "  " << names[q] << ": " << 100.0 * share << " % in its colour\n";
    EXPECT_GT(share, 0.9) << names[q];
  }
  return bounds;
}

}  // namespace lutex::testing
