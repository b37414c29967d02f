#include "texturing/gltf_texture_pages.h"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>
#include <tiny_gltf.h>

namespace lutex {

std::vector<cv::Mat> ReadGltfTexturePages(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool binary = path.extension() == ".glb";
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path.string())
                             : loader.LoadASCIIFromFile(&model, &error, &warning, path.string());
  if (!loaded) throw std::runtime_error(path.string() + ": cannot read the glTF model (" + error + ")");
  std::vector<cv::Mat> pages;
  for (const tinygltf::Image& image : model.images) {
    if (image.bits != 8 || (image.component != 3 && image.component != 4) || image.image.empty()) {
      throw std::runtime_error(path.string() + ": image '" + image.name + "' is not 8-bit RGB(A)");
    }
    const cv::Mat decoded(image.height, image.width, CV_8UC(image.component),
                          const_cast<unsigned char*>(image.image.data()));
    cv::Mat bgr;
    cv::cvtColor(decoded, bgr, image.component == 4 ? cv::COLOR_RGBA2BGR : cv::COLOR_RGB2BGR);
    pages.push_back(bgr);
  }
  return pages;
}

}  // namespace lutex
