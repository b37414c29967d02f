#include "colmap_integration/texture_workspace.h"

#include <chrono>
#include <stdexcept>

#include "colmap_integration/confidence_map_io.h"
#include "colmap_integration/restore_workspace.h"
#include "colmap_integration/sparse_model_io.h"
#include "colmap_integration/workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/util/logging.h"
#include "texturing/textured_mesh_io.h"

namespace lutex {

namespace fs = std::filesystem;

void TextureOptions::Check() const {
  if (workspace.empty()) throw std::invalid_argument("--workspace is required");
  if (mesh.empty()) throw std::invalid_argument("--mesh is required");
  if (!output.empty()) CheckTexturedMeshPath(output);
  if (page_encoding == ImageEncoding::kFloat) throw std::invalid_argument("pages are srgb8 or linear16");
  baking.Check();
}

TextureSummary TextureWorkspace(const TextureOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const Workspace workspace = FindWorkspace(options.workspace);
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  TextureSummary summary;
  summary.images = options.images;
  if (summary.images.empty()) {
    summary.images = workspace.RestoredDir();
    if (!fs::is_directory(summary.images)) {
      summary.images = workspace.images_dir;
      LogWarning() << "texture: " << workspace.RestoredDir().string()
                   << " does not exist; texturing the unrestored images of " << summary.images.string()
                   << " (run lutex restore first for albedo)";
    }
  }
  if (!fs::is_directory(summary.images)) throw std::runtime_error(summary.images.string() + ": no such folder");
  if (!options.ignore_confidence) {
    summary.confidence = options.confidence;
    if (summary.confidence.empty()) {
      const fs::path beside = ConfidenceDirOf(summary.images);
      if (fs::is_directory(beside)) summary.confidence = beside;
    } else if (!fs::is_directory(summary.confidence)) {
      throw std::runtime_error(summary.confidence.string() + ": no such folder");
    }
  }
  std::vector<TextureView> views;
  std::vector<fs::path> image_paths, confidence_paths;
  for (const auto& [id, image] : model.images) {
    const fs::path path = FindRestoredImage(summary.images, image.name);
    if (path.empty()) {
      throw std::runtime_error((summary.images / image.name).string() + ": no such image (image " +
                               std::to_string(id) + " of the model)");
    }
    image_paths.push_back(path);
    if (!summary.confidence.empty()) {
      const fs::path confidence = ConfidenceMapPath(summary.confidence, image.name);
      if (!fs::exists(confidence)) throw std::runtime_error(confidence.string() + ": no such confidence map");
      confidence_paths.push_back(confidence);
    }
    views.push_back({image.name, model.cameras.at(image.camera_id), image.cam_from_world});
  }
  const Mesh mesh = ReadMesh(options.mesh);
  const fs::path output = options.output.empty() ? workspace.ModelPath() : options.output;

  ViewImageSource source;
  source.linear_rgb = [&](std::size_t v) {
    const cv::Mat image = ReadLinearImage(image_paths[v], options.image_encoding);
    if (image.cols != static_cast<int>(views[v].camera.width) || image.rows != static_cast<int>(views[v].camera.height)) {
      throw std::runtime_error(image_paths[v].string() + ": the image is " + std::to_string(image.cols) + "x" +
                               std::to_string(image.rows) + " but its camera is " +
                               std::to_string(views[v].camera.width) + "x" + std::to_string(views[v].camera.height));
    }
    return image;
  };
  if (!confidence_paths.empty()) {
    source.confidence = [&](std::size_t v) { return ReadConfidenceMap(confidence_paths[v], views[v].camera); };
  }
  TextureBakingResult result = BakeTexture(mesh, views, source, options.baking);
  summary.baking = result.summary;
  summary.written = WriteTexturedMesh(result.textured, output, options.page_encoding);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace lutex
