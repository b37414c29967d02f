#include "colmap_integration/stages/workspace_views.h"

#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "colmap_integration/io/confidence_map_io.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

// A picture whose every pixel differs from its neighbours, so that a window read from the wrong place
// cannot match: value = f(col, row, channel).
cv::Mat Gradient(int width, int height, int depth) {
  const double full = depth == CV_8U ? 255.0 : 65535.0;
  cv::Mat picture(height, width, CV_MAKETYPE(depth, 3));
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      for (int c = 0; c < 3; ++c) {
        const double value = full * (0.05 + 0.9 * ((col * 7 + row * 13 + c * 29) % 97) / 96.0);
        if (depth == CV_8U) {
          picture.at<cv::Vec3b>(row, col)[c] = cv::saturate_cast<unsigned char>(value);
        } else {
          picture.at<cv::Vec3w>(row, col)[c] = cv::saturate_cast<unsigned short>(value);
        }
      }
    }
  }
  return picture;
}

double MaxDifference(const cv::Mat& a, const cv::Mat& b) {
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.type(), b.type());
  if (a.size() != b.size() || a.type() != b.type()) return 1e9;
  return cv::norm(a, b, cv::NORM_INF);
}

// A window of a view, read through the workspace's source, is the same window of the whole image read
// and linearised on its own, for 8-bit sRGB and 16-bit linear files, and so is the confidence map's; with
// a picture cache, the image and the map are each decoded once for all the reads.
TEST(WorkspaceViews, AWindowOfAViewIsThatWindowOfTheWholeImage) {
  testing::TempDir dir;
  constexpr int kWidth = 64, kHeight = 48;
  for (const std::size_t cache_bytes : {std::size_t{0}, std::size_t{1} << 20})
  for (const ImageEncoding encoding : {ImageEncoding::kSrgb8, ImageEncoding::kLinear16}) {
    const std::string name = ImageEncodingName(encoding) + (cache_bytes > 0 ? " cached" : "");
    WorkspaceViews found;
    found.pictures = std::make_shared<PictureCache>(cache_bytes);
    found.image_encoding = encoding;
    found.views.push_back({name, Camera::Pinhole(1, kWidth, kHeight, 50.0, 50.0), Rigid3d()});
    found.image_paths.push_back(dir.path() / (name + ".png"));
    ASSERT_TRUE(cv::imwrite(found.image_paths[0].string(),
                            Gradient(kWidth, kHeight, encoding == ImageEncoding::kSrgb8 ? CV_8U : CV_16U)));
    found.confidence_paths.push_back(dir.path() / (name + "_confidence.png"));
    ASSERT_TRUE(cv::imwrite(found.confidence_paths[0].string(), Gradient(kWidth, kHeight, CV_8U)));
    const ViewImageSource source = found.Source();

    const cv::Mat whole = ReadLinearImage(found.image_paths[0], encoding);
    const cv::Mat whole_confidence = ReadConfidenceMap(found.confidence_paths[0], found.views[0].camera);
    EXPECT_EQ(MaxDifference(LoadViewImage(source, found.views, 0), whole), 0.0) << name;
    for (const cv::Rect window : {cv::Rect(0, 0, 1, 1), cv::Rect(5, 7, 20, 11), cv::Rect(40, 30, 24, 18)}) {
      EXPECT_EQ(MaxDifference(LoadViewImage(source, found.views, 0, window), whole(window)), 0.0) << name;
      EXPECT_EQ(MaxDifference(LoadViewConfidence(source, found.views, 0, window), whole_confidence(window)), 0.0)
          << name;
    }
    EXPECT_EQ(found.pictures->decodes(), cache_bytes > 0 ? 2u : 7u) << name;
    EXPECT_EQ(source.is_held(0), cache_bytes > 0) << name;
  }
}

// The memory check counts the cache's budget, or what every view's picture and confidence map come to
// when that is less.
TEST(WorkspaceViews, ThePictureCacheIsCountedAtItsBudgetOrAtWhatTheViewsComeTo) {
  SparseModel model;
  model.cameras.emplace(1, Camera::Pinhole(1, 100, 50, 50.0, 50.0));
  for (std::uint32_t id = 1; id <= 4; ++id) model.images[id].camera_id = 1;
  // 4 views of 5000 pixels: 3 bytes a pixel for an 8-bit picture, 6 for 16 bits, 12 for float; 3 for the map.
  EXPECT_EQ(PictureCacheBytes(model, ImageEncoding::kSrgb8, 1 << 20), 4 * 5000 * (3 + 3));
  EXPECT_EQ(PictureCacheBytes(model, ImageEncoding::kLinear16, 1 << 20), 4 * 5000 * (6 + 3));
  EXPECT_EQ(PictureCacheBytes(model, ImageEncoding::kFloat, 1 << 20), 4 * 5000 * (12 + 3));
  EXPECT_EQ(PictureCacheBytes(model, ImageEncoding::kSrgb8, 100000), 100000);
  EXPECT_EQ(PictureCacheBytes(model, ImageEncoding::kSrgb8, 0), 0);
}

TEST(WorkspaceViews, AnImageOfAnotherSizeIsAnErrorNamingTheFile) {
  testing::TempDir dir;
  WorkspaceViews found;
  found.views.push_back({"a.png", Camera::Pinhole(1, 64, 48, 50.0, 50.0), Rigid3d()});
  found.image_paths.push_back(dir.path() / "a.png");
  ASSERT_TRUE(cv::imwrite(found.image_paths[0].string(), Gradient(48, 64, CV_8U)));
  const ViewImageSource source = found.Source();
  try {
    LoadViewImage(source, found.views, 0, cv::Rect(0, 0, 8, 8));
    FAIL() << "an image of the wrong size was read";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(found.image_paths[0].string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lutex
