#include "colmap_integration/stages/restore_workspace.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <chrono>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include "colmap_integration/io/confidence_map_io.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/calibration/exposure_record.h"
#include "lib/image/image_header.h"
#include "lib/raycast/forward_scatter_removal.h"
#include "lib/raycast/images_by_camera.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/io/workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/lut/lut_file.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

// The coverage LUT to use, or empty; an explicit one must exist and match the LUT's grid.
fs::path CoveragePath(const RestoreOptions& options) {
  if (options.ignore_coverage) return {};
  if (!options.coverage.empty()) return options.coverage;
  const fs::path beside = CoverageLutPath(options.lut);
  return fs::exists(beside) ? beside : fs::path();
}

void CheckSameGrid(const FrustumLut& lut, const fs::path& lut_path, const FrustumLut& coverage,
                   const fs::path& coverage_path) {
  if (!(lut.grid() == coverage.grid())) {
    throw std::runtime_error(coverage_path.string() + ": the coverage is for another LUT grid than " +
                             lut_path.string());
  }
}

}  // namespace

fs::path RestoredImagePath(const fs::path& output, const std::string& name, ImageEncoding encoding) {
  fs::path path = output / name;
  const std::string extension = path.extension().string();
  if (encoding == ImageEncoding::kFloat) {
    path.replace_extension(".exr");
  } else if (encoding == ImageEncoding::kLinear16 && extension != ".png" && extension != ".tif" && extension != ".tiff") {
    path.replace_extension(".png");
  }
  return path;
}

fs::path FindRestoredImage(const fs::path& folder, const std::string& name) {
  for (const ImageEncoding encoding : {ImageEncoding::kSrgb8, ImageEncoding::kLinear16, ImageEncoding::kFloat}) {
    const fs::path path = RestoredImagePath(folder, name, encoding);
    if (fs::exists(path)) return path;
  }
  return {};
}

void RestoreOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (mesh.empty()) throw OptionError("{mesh} is required");
  if (lut.empty()) throw OptionError("{lut} is required");
  if (output_encoding != "same") ParseImageEncoding(output_encoding);
  restoration.Check();
  smoothing.Check();
}

namespace {

// What restore reads and writes (output_policy.h).
InputsAndOutputs PathsOf(const RestoreOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(options.mesh, "the mesh");
  paths.AddInput(options.lut, "the LUT");
  paths.AddInput(CoveragePath(options), "the LUT's coverage");
  if (fs::exists(ExposureRecordPath(options.lut))) paths.AddInput(ExposureRecordPath(options.lut), "the LUT's exposure record");
  const fs::path output = options.output.empty() ? workspace.RestoredDir() : options.output;
  paths.AddOutput(output);
  paths.AddOutput(ConfidenceDirOf(output));
  return paths;
}

}  // namespace

RestoreSummary RestoreWorkspace(const RestoreOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  return RestoreWorkspace(options, LoadedDive(options.workspace, options.mesh));
}

RestoreSummary RestoreWorkspace(const RestoreOptions& options, const LoadedDive& dive) {
  options.Check();
  const InputsAndOutputs paths = PathsOf(options, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  CheckStageMemory("restore", dive, options.num_threads, kImageStageBytesPerPixel, options.memory_limit_bytes);
  const auto start = std::chrono::steady_clock::now();
  const Workspace& workspace = dive.workspace();
  const SparseModel& model = dive.model();
  const FrustumLut lut = ReadLut(options.lut);
  const fs::path coverage_path = CoveragePath(options);
  std::optional<FrustumLut> coverage;
  if (!coverage_path.empty()) {
    coverage = ReadLut(coverage_path);
    CheckSameGrid(lut, options.lut, *coverage, coverage_path);
  }
  // The exposure the LUT is for, and the fitted gains (exposure_record.h); none for LUTs calibrated before.
  std::optional<ExposureRecord> exposure;
  if (fs::exists(ExposureRecordPath(options.lut))) {
    exposure = ReadExposureRecord(ExposureRecordPath(options.lut));
    if (!exposure->fitted_gains.empty() && !exposure->HasGainsFor(workspace.images_dir)) {
      LogWarning() << ExposureRecordPath(options.lut).string() << ": its fitted gains are for the images of "
                   << exposure->fitted_images.string() << ", not these; only EXIF exposure is applied";
    }
  }
  for (const auto& [id, camera] : model.cameras) {
    if (static_cast<int>(camera.width) != lut.grid().image_width ||
        static_cast<int>(camera.height) != lut.grid().image_height) {
      throw std::runtime_error(options.lut.string() + ": the LUT is for " + std::to_string(lut.grid().image_width) + "x" +
                               std::to_string(lut.grid().image_height) + " images but camera " + std::to_string(id) +
                               " is " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
    }
  }
  for (const auto& [id, image] : model.images) {
    if (!fs::exists(workspace.images_dir / image.name)) {
      throw std::runtime_error((workspace.images_dir / image.name).string() + ": no such image (image " +
                               std::to_string(id) + " of the model)");
    }
  }
  const RaycastScene& scene = dive.scene();
  const ImageEncoding output_encoding =
      options.output_encoding == "same" ? options.input_encoding : ParseImageEncoding(options.output_encoding);

  RestoreSummary summary;
  summary.coverage = coverage_path;
  summary.output = options.output.empty() ? workspace.RestoredDir() : options.output;
  summary.confidence_output = ConfidenceDirOf(summary.output);
  const auto outputs_of = [&](const Image& image) {
    return std::vector<fs::path>{RestoredImagePath(summary.output, image.name, output_encoding),
                                 ConfidenceMapPath(summary.confidence_output, image.name)};
  };
  SparseModel todo = options.skip_done ? WithoutDoneImages(model, outputs_of) : model;
  summary.num_skipped = model.images.size() - todo.images.size();
  // Every image's header before the first write: a bad file anywhere stops the command here, with
  // nothing written (or is skipped, with skip_bad_images).
  std::mutex bad_mutex;
  const auto skip_or_throw = [&](const std::runtime_error& error) {
    if (!options.skip_bad_images) throw error;
    LogWarning() << error.what() << "; skipped (--skip-bad-images)";
    std::lock_guard<std::mutex> lock(bad_mutex);
    summary.bad_images.push_back(error.what());
  };
  for (auto it = todo.images.begin(); it != todo.images.end();) {
    const Camera& camera = todo.cameras.at(it->second.camera_id);
    try {
      CheckImageHeader(workspace.images_dir / it->second.name, static_cast<int>(camera.width),
                       static_cast<int>(camera.height), options.input_encoding);
      ++it;
    } catch (const std::runtime_error& error) {
      skip_or_throw(error);
      it = todo.images.erase(it);
    }
  }
  double confidence_sum = 0.0;
  std::size_t surface_pixels = 0;
  std::mutex summary_mutex;
  // The outputs of the image each worker is on, reused from image to image.
  std::vector<RestoredImage> worker_outputs(static_cast<std::size_t>(ResolveNumThreads(options.num_threads)));
  ForEachImageWithMaps(todo, scene, options.num_threads, "restore",
                       [&](const Image& image, const CameraRays& rays, const GeometryMaps& maps, int worker) {
    RestoredImage& restored = worker_outputs[static_cast<std::size_t>(worker)];
    const fs::path input = workspace.images_dir / image.name;
    cv::Mat observed;
    try {
      observed = ReadLinearImage(input, options.input_encoding);
      ExpectCameraSize(input, observed.cols, observed.rows, rays.width(), rays.height());
    } catch (const std::runtime_error& error) {
      skip_or_throw(error);  // unreadable pixels behind a sound header (a truncated file)
      return;
    }
    bool missing_exif = false;
    const double gain = exposure ? exposure->GainOf(workspace.images_dir, image.name, &missing_exif) : 1.0;
    // As the calibration did before it fitted the LUT: the scattering taken out of the light from the
    // surfaces, the LUT's backscatter (at this image's exposure) set aside.
    if (!lut.grid().forward_scatter.IsNone()) {
      observed = WithoutForwardScatter(observed, maps, rays, lut.grid().forward_scatter,
                                       options.restoration.saturation_level, BackscatterAtSurfaces(lut, maps, gain));
    }
    // Divided by its gain, the image's clipping level and noise are divided too.
    RestorationOptions restoration = options.restoration;
    if (gain != 1.0) {
      observed /= gain;
      restoration.saturation_level /= gain;
      restoration.shot_noise /= std::sqrt(gain);
      restoration.read_noise /= gain;
    }
    RestoreImage(observed, maps, rays, lut, restoration, coverage ? &*coverage : nullptr, &restored);
    const cv::Mat surfaces = maps.depth == maps.depth;
    if (options.smoothing.enabled) restored.albedo = SmoothNoiseAdaptively(restored.albedo, surfaces, options.smoothing);
    const std::vector<fs::path> outputs = outputs_of(image);
    WriteLinearImage(restored.albedo, outputs[0], output_encoding);
    WriteConfidenceMap(restored.confidence, outputs[1]);
    const cv::Scalar total = cv::sum(restored.confidence);
    std::lock_guard<std::mutex> lock(summary_mutex);
    confidence_sum += total[0] + total[1] + total[2];
    surface_pixels += static_cast<std::size_t>(cv::countNonZero(surfaces));
    ++summary.num_images;
    summary.num_exposure_adjusted += gain != 1.0 ? 1 : 0;
    if (missing_exif) summary.missing_exif.push_back(image.name);
  });
  std::sort(summary.missing_exif.begin(), summary.missing_exif.end());
  if (!summary.missing_exif.empty()) {
    LogWarning() << summary.missing_exif.size() << " image(s) lack the EXIF exposure settings the LUT was calibrated "
                 << "with (first: " << summary.missing_exif.front() << "); they are restored as if at its reference exposure";
  }
  summary.mean_confidence = surface_pixels ? confidence_sum / (3.0 * static_cast<double>(surface_pixels)) : 0.0;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintRestoreSummary(std::ostream& out, const RestoreSummary& summary) {
  out << "restore: " << summary.num_images << " images in " << std::fixed << std::setprecision(1)
            << summary.seconds << " s; mean confidence " << std::setprecision(2) << summary.mean_confidence << "\n"
            << "  restored images:  " << summary.output.string() << "\n"
            << "  confidence maps:  " << summary.confidence_output.string() << "\n"
            << "  LUT coverage:     " << (summary.coverage.empty() ? std::string("not used") : summary.coverage.string())
            << "\n"
            << "  exposure:         " << summary.num_exposure_adjusted << " image(s) scaled by their EXIF or fitted gain"
            << (summary.missing_exif.empty() ? std::string()
                                             : ", " + std::to_string(summary.missing_exif.size()) + " without EXIF")
            << "\n";
  if (!summary.bad_images.empty()) {
    out << "  skipped as unreadable (--skip-bad-images): " << summary.bad_images.size() << " image(s)\n";
    for (const std::string& bad : summary.bad_images) out << "    " << bad << "\n";
  }
}

}  // namespace lutex
