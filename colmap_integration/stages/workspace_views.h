#pragma once

// The posed views of a workspace that texture and mosaic bake from: one per registered image of the
// model, with its image (restored by default) and confidence map found and checked before any work.
//
//   images       folder with one image per registered image, by the model's name; a restored image
//                written as .png or .exr (lutex restore does so for 16-bit and float output) is found
//                under that extension too. Default: W/lutex/restored when it exists, else W/images (the
//                result then shows the light and water, not albedo: a warning says so).
//   confidence   IMAGES_confidence/NAME.png (as lutex restore writes them) when that folder exists; the
//                view selection and the fusion then trust each pixel as much as the restoration did.
//
// A stage that reads a view many times (lutex tiles and mosaic: once per tile that sees it) keeps the decoded
// pictures and confidence maps (as stored: 8-bit or 16-bit) of the most recently read views within
// `picture_cache_bytes` (lib/image/picture_cache.h).

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/output_policy.h"
#include "lib/geometry/sparse_model.h"
#include "lib/image/image_io.h"
#include "lib/image/picture_cache.h"
#include "texturing/texture_views.h"

namespace lutex {

// What `lutex tiles` and `lutex mosaic` keep by default: 384 MiB holds ten 12 MP 8-bit pictures (README,
// 'lutex tiles': what 128 to 384 MiB gave at 12 MP; 'lutex mosaic': 388 reads of 24 views without it).
constexpr std::size_t kDefaultPictureCacheBytes = std::size_t{384} << 20;

struct WorkspaceViewsOptions {
  std::filesystem::path images;      // empty: see above
  std::filesystem::path confidence;  // empty: IMAGES_confidence when it exists
  bool ignore_confidence = false;    // trust every pixel equally
  ImageEncoding image_encoding = ImageEncoding::kSrgb8;
  std::size_t picture_cache_bytes = 0;  // decoded pictures kept for reading again; 0: none
};

struct WorkspaceViews {
  std::filesystem::path images;
  std::filesystem::path confidence;  // empty when not used
  std::vector<TextureView> views;
  std::vector<std::filesystem::path> image_paths;
  std::vector<std::filesystem::path> confidence_paths;  // empty when not used
  ImageEncoding image_encoding = ImageEncoding::kSrgb8;
  std::shared_ptr<PictureCache> pictures = std::make_shared<PictureCache>(0);

  // Reads a view's image (checked against its camera's size) and confidence map. Refers to this object.
  ViewImageSource Source() const;
};

// What the decoded-picture cache can come to for `model`'s views: `budget_bytes`, or less when every view's
// picture (of `encoding`) and confidence map fit in it. For memory estimates: a small dive's stage is not
// charged a budget it cannot fill.
double PictureCacheBytes(const SparseModel& model, ImageEncoding encoding, std::size_t budget_bytes);

// Throws std::runtime_error naming the folder, image or map that is missing. `stage` starts the warning
// ("texture", "mosaic").
WorkspaceViews FindWorkspaceViews(const Workspace& workspace, const SparseModel& model,
                                  const WorkspaceViewsOptions& options, const std::string& stage);

// What a stage that bakes from the workspace's views reads (output_policy.h): the workspace, the mesh, the
// images (`images_are`: "the images to texture from"), their confidence maps and the georeference file.
// The images are found later (restored or not), so the default folder counts as an input either way.
InputsAndOutputs ViewStageInputs(const Workspace& workspace, const std::filesystem::path& mesh,
                                 const WorkspaceViewsOptions& options, const std::string& images_are);

}  // namespace lutex
