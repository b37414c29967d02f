#include "colmap_integration/stages/workspace_views.h"

#include <algorithm>
#include <stdexcept>

#include "colmap_integration/io/confidence_map_io.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "lib/image/image_header.h"
#include "lib/util/logging.h"

namespace lutex {

namespace fs = std::filesystem;

WorkspaceViews FindWorkspaceViews(const Workspace& workspace, const SparseModel& model,
                                  const WorkspaceViewsOptions& options, const std::string& stage) {
  WorkspaceViews found;
  found.image_encoding = options.image_encoding;
  found.pictures = std::make_shared<PictureCache>(options.picture_cache_bytes);
  found.images = options.images;
  if (found.images.empty()) {
    found.images = workspace.RestoredDir();
    if (!fs::is_directory(found.images)) {
      found.images = workspace.images_dir;
      LogWarning() << stage << ": " << workspace.RestoredDir().string() << " does not exist; using the unrestored images of "
                   << found.images.string() << " (run lutex restore first for albedo)";
    }
  }
  if (!fs::is_directory(found.images)) throw std::runtime_error(found.images.string() + ": no such folder");
  if (!options.ignore_confidence) {
    found.confidence = options.confidence;
    if (found.confidence.empty()) {
      const fs::path beside = ConfidenceDirOf(found.images);
      if (fs::is_directory(beside)) found.confidence = beside;
    } else if (!fs::is_directory(found.confidence)) {
      throw std::runtime_error(found.confidence.string() + ": no such folder");
    }
  }
  for (const auto& [id, image] : model.images) {
    const fs::path path = FindRestoredImage(found.images, image.name);
    if (path.empty()) {
      throw std::runtime_error((found.images / image.name).string() + ": no such image (image " + std::to_string(id) +
                               " of the model)");
    }
    found.image_paths.push_back(path);
    if (!found.confidence.empty()) {
      const fs::path confidence = ConfidenceMapPath(found.confidence, image.name);
      if (!fs::exists(confidence)) throw std::runtime_error(confidence.string() + ": no such confidence map");
      found.confidence_paths.push_back(confidence);
    }
    found.views.push_back({image.name, model.cameras.at(image.camera_id), image.cam_from_world});
  }
  return found;
}

namespace {

// The cache's keys: a view's picture and its confidence map.
std::size_t PictureKey(std::size_t view) { return 2 * view; }
std::size_t ConfidenceKey(std::size_t view) { return 2 * view + 1; }

}  // namespace

ViewImageSource WorkspaceViews::Source() const {
  ViewImageSource source;
  source.linear_rgb = [this](std::size_t v, const cv::Rect& window) {
    const cv::Mat picture = pictures->Get(PictureKey(v), [this, v] {
      cv::Mat read = ReadEncodedPicture(image_paths[v], image_encoding);
      ExpectCameraSize(image_paths[v], read.cols, read.rows, static_cast<int>(views[v].camera.width),
                       static_cast<int>(views[v].camera.height));
      return read;
    });
    return DecodeLinearImage(window.empty() ? picture : picture(window), image_encoding);
  };
  source.is_held = [this](std::size_t v) {
    return pictures->Holds(PictureKey(v)) && (confidence_paths.empty() || pictures->Holds(ConfidenceKey(v)));
  };
  if (!confidence_paths.empty()) {
    source.confidence = [this](std::size_t v, const cv::Rect& window) {
      const cv::Mat encoded = pictures->Get(
          ConfidenceKey(v), [this, v] { return ReadEncodedConfidenceMap(confidence_paths[v], views[v].camera); });
      return DecodeConfidenceMap(encoded, window);
    };
  }
  return source;
}

double PictureCacheBytes(const SparseModel& model, ImageEncoding encoding, std::size_t budget_bytes) {
  const double picture_bytes_per_pixel = encoding == ImageEncoding::kSrgb8 ? 3.0 : encoding == ImageEncoding::kLinear16 ? 6.0 : 12.0;
  const double confidence_bytes_per_pixel = 3.0;
  double all_bytes = 0.0;
  for (const auto& [id, image] : model.images) {
    const Camera& camera = model.cameras.at(image.camera_id);
    all_bytes += double(camera.width) * double(camera.height) * (picture_bytes_per_pixel + confidence_bytes_per_pixel);
  }
  return std::min(double(budget_bytes), all_bytes);
}

InputsAndOutputs ViewStageInputs(const Workspace& workspace, const std::filesystem::path& mesh,
                                 const WorkspaceViewsOptions& options, const std::string& images_are) {
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(mesh, "the mesh");
  paths.AddInput(options.images.empty() ? workspace.RestoredDir() : options.images, images_are);
  paths.AddInput(options.confidence, "the confidence maps");
  paths.AddInput(workspace.GeoreferencePath(), "the georeference file");
  return paths;
}

}  // namespace lutex
