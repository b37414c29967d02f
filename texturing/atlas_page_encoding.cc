#include "texturing/atlas_page_encoding.h"

#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

namespace lutex {

std::vector<unsigned char> EncodeAtlasPage(const cv::Mat& page, ImageEncoding encoding) {
  if (encoding == ImageEncoding::kFloat) throw std::invalid_argument("atlas pages are PNG: srgb8 or linear16");
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", EncodeLinearImage(page, encoding), bytes)) {
    throw std::runtime_error("could not encode an atlas page as PNG");
  }
  return bytes;
}

}  // namespace lutex
