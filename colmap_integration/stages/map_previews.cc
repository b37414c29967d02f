#include "colmap_integration/stages/map_previews.h"

#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "lib/geo/geo_raster_preview.h"
#include "lib/image/image_io.h"

namespace lutex {

namespace {

const cv::Vec3b kNodata(128, 128, 128);

// A white bar with a dark outline and its length, at the bottom left.
void DrawScaleBar(cv::Mat& bgr8, double metres_per_pixel, double metres) {
  const int length = static_cast<int>(std::lround(metres / metres_per_pixel));
  const int x = 12, y = bgr8.rows - 14;
  cv::rectangle(bgr8, {x - 1, y - 4}, {x + length + 1, y + 4}, cv::Scalar(20, 20, 20), cv::FILLED);
  cv::rectangle(bgr8, {x, y - 3}, {x + length, y + 3}, cv::Scalar(255, 255, 255), cv::FILLED);
  char label[32];
  std::snprintf(label, sizeof(label), metres >= 1.0 ? "%.0f m" : "%.2f m", metres);
  cv::putText(bgr8, label, {x, y - 9}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(20, 20, 20), 3, cv::LINE_AA);
  cv::putText(bgr8, label, {x, y - 9}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

MapPreview Finish(cv::Mat bgr8, double metres_per_pixel, const std::string& crs_name) {
  MapPreview preview;
  preview.metres_per_pixel = metres_per_pixel;
  preview.scale_bar_metres = ScaleBarLength(metres_per_pixel * bgr8.cols);
  preview.crs_name = crs_name;
  DrawScaleBar(bgr8, metres_per_pixel, preview.scale_bar_metres);
  preview.bgr8 = bgr8;
  return preview;
}

}  // namespace

double ScaleBarLength(double width_metres) {
  double best = 0.01;
  for (double decade = 0.01; decade <= 10000.0; decade *= 10.0) {
    for (double step : {1.0, 2.0, 5.0}) {
      if (step * decade <= 0.25 * width_metres) best = step * decade;
    }
  }
  return best;
}

MapPreview OrthomosaicPreview(const std::filesystem::path& ortho, int max_side) {
  const GeoRasterPreview raster = ReadGeoRasterPreview(ortho, max_side);
  const int bands = raster.samples.channels();
  cv::Mat bgr8(raster.samples.size(), CV_8UC3);
  for (int r = 0; r < bgr8.rows; ++r) {
    const float* in = raster.samples.ptr<float>(r);
    for (int c = 0; c < bgr8.cols; ++c, in += bands) {
      if (bands >= 4 && !(in[3] > 0.0f)) {
        bgr8.at<cv::Vec3b>(r, c) = kNodata;
        continue;
      }
      cv::Vec3b& out = bgr8.at<cv::Vec3b>(r, c);
      for (int k = 0; k < 3; ++k) {
        const double value = in[std::min(k, bands - 1)];
        const double srgb = raster.sixteen_bit ? LinearToSrgb(value / 65535.0) : value / 255.0;
        out[2 - k] = cv::saturate_cast<uchar>(255.0 * srgb + 0.5);
      }
    }
  }
  return Finish(bgr8, raster.grid.gsd, raster.crs_name);
}

MapPreview DemPreview(const std::filesystem::path& dem, int max_side) {
  const GeoRasterPreview raster = ReadGeoRasterPreview(dem, max_side);
  cv::Mat heights;
  cv::extractChannel(raster.samples, heights, 0);
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (int r = 0; r < heights.rows; ++r) {
    for (int c = 0; c < heights.cols; ++c) {
      const float z = heights.at<float>(r, c);
      if (std::isfinite(z)) {
        low = std::min(low, double(z));
        high = std::max(high, double(z));
      }
    }
  }
  cv::Mat levels(heights.size(), CV_8UC1, cv::Scalar(0));
  const double span = high > low ? high - low : 1.0;
  for (int r = 0; r < heights.rows; ++r) {
    for (int c = 0; c < heights.cols; ++c) {
      const float z = heights.at<float>(r, c);
      if (std::isfinite(z)) levels.at<uchar>(r, c) = cv::saturate_cast<uchar>(255.0 * (z - low) / span);
    }
  }
  cv::Mat bgr8;
  cv::applyColorMap(levels, bgr8, cv::COLORMAP_VIRIDIS);
  for (int r = 0; r < heights.rows; ++r) {
    for (int c = 0; c < heights.cols; ++c) {
      if (!std::isfinite(heights.at<float>(r, c))) bgr8.at<cv::Vec3b>(r, c) = kNodata;
    }
  }
  MapPreview preview = Finish(bgr8, raster.grid.gsd, raster.crs_name);
  preview.low = std::isfinite(low) ? low : 0.0;
  preview.high = std::isfinite(high) ? high : 0.0;
  return preview;
}

}  // namespace lutex
