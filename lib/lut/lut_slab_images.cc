#include "lib/lut/lut_slab_images.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>


#include "lib/image/image_io.h"

namespace lutex {

LutSlabImages RenderLutSlabs(const FrustumLut& lut, int width) {
  const FrustumLutGrid& grid = lut.grid();
  const int height = std::max(1, width * grid.image_height / grid.image_width);
  LutSlabImages images;
  for (int n = 0; n < grid.NumNodes(); ++n) {
    images.alpha_scale = std::max(images.alpha_scale, lut.node(n).alpha.maxCoeff());
    images.beta_scale = std::max(images.beta_scale, lut.node(n).beta.maxCoeff());
  }
  const double alpha_gain = images.alpha_scale > 0 ? 255.0 / images.alpha_scale : 0.0;
  const double beta_gain = images.beta_scale > 0 ? 255.0 / images.beta_scale : 0.0;
  for (int k = 0; k < grid.nz; ++k) {
    cv::Mat alpha(height, width, CV_8UC3), beta(height, width, CV_8UC3);
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        const LutNode value = lut.Lookup((col + 0.5) * grid.image_width / width, (row + 0.5) * grid.image_height / height,
                                         grid.SlabDepth(k));
        // OpenCV stores BGR.
        alpha.at<cv::Vec3b>(row, col) = cv::Vec3b(cv::saturate_cast<uchar>(alpha_gain * value.alpha[2]),
                                                  cv::saturate_cast<uchar>(alpha_gain * value.alpha[1]),
                                                  cv::saturate_cast<uchar>(alpha_gain * value.alpha[0]));
        beta.at<cv::Vec3b>(row, col) = cv::Vec3b(cv::saturate_cast<uchar>(beta_gain * value.beta[2]),
                                                 cv::saturate_cast<uchar>(beta_gain * value.beta[1]),
                                                 cv::saturate_cast<uchar>(beta_gain * value.beta[0]));
      }
    }
    images.alpha.push_back(alpha);
    images.beta.push_back(beta);
  }
  return images;
}

void WriteLutSlabImages(const FrustumLut& lut, const std::filesystem::path& folder, int width) {
  const LutSlabImages images = RenderLutSlabs(lut, width);
  for (std::size_t k = 0; k < images.alpha.size(); ++k) {
    char name[32];
    for (const auto& [kind, picture] : {std::pair<const char*, const cv::Mat&>("alpha", images.alpha[k]),
                                        std::pair<const char*, const cv::Mat&>("beta", images.beta[k])}) {
      std::snprintf(name, sizeof(name), "slab_%02zu_%s.png", k, kind);
      WriteEncodedImage(picture, folder / name);
    }
  }
}

}  // namespace lutex
