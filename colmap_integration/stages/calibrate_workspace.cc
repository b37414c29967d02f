#include "colmap_integration/stages/calibrate_workspace.h"

#include <iomanip>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/raycast/forward_scatter_removal.h"
#include "lib/raycast/images_by_camera.h"
#include "lib/model/light_rig_json.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/calibration/survey_correspondences.h"
#include "colmap_integration/io/workspace.h"
#include "lib/calibration/charuco_target.h"
#include "lib/calibration/exposure_gains.h"
#include "lib/calibration/chessboard_target.h"
#include "lib/calibration/backscatter_set_aside.h"
#include "lib/calibration/forward_scatter_estimate.h"
#include "lib/calibration/pure_water_sampling.h"
#include "lib/calibration/reshading.h"
#include "lib/calibration/targets.h"
#include "lib/geometry/mesh_io.h"
#include "lib/lut/lut_file.h"
#include "lib/lut/lut_slab_images.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/file_streams.h"
#include "lib/image/exposure_settings.h"
#include "lib/util/logging.h"
#include "lib/util/median.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"
#include "lib/util/option_error.h"
#include "lib/util/json_fields.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

Water ReferenceWater(const CalibrateOptions& options) {
  return options.calibration.in_air ? Water::Air() : *WaterPreset(options.reference_water);
}

// Coarse-to-fine levels ending at nx x ny: a tenth and a half of it where they divide (paper: 4x3, 20x15).
std::vector<std::pair<int, int>> DefaultLevels(int nx, int ny) {
  std::vector<std::pair<int, int>> levels;
  for (int divisor : {10, 2}) {
    if (nx % divisor == 0 && ny % divisor == 0 && nx / divisor >= 1 && ny / divisor >= 1) {
      levels.emplace_back(nx / divisor, ny / divisor);
    }
  }
  levels.emplace_back(nx, ny);
  return levels;
}

const Camera& SingleImageSize(const SparseModel& model, const fs::path& where) {
  const Camera& first = model.cameras.begin()->second;
  for (const auto& [id, camera] : model.cameras) {
    if (camera.width != first.width || camera.height != first.height) {
      throw std::runtime_error(where.string() + ": cameras of different image sizes; a LUT is for one size");
    }
  }
  return first;
}

// Known-colour observations from the images of `workspace` (the targets' geometry from `scene`), per image
// in parallel, gathered in image order so the solve is the same at any thread count.
ObservationSet KnownColorObservations(const CalibrateOptions& options, const std::vector<Target>& targets,
                                      const Workspace& workspace, const SparseModel& model, const RaycastScene& scene,
                                      const BackscatterSetAside& backscatter) {
  KnownColorSamplingOptions sampling = options.sampling;
  sampling.shading = options.calibration.grid.shading;
  std::map<std::uint32_t, std::vector<KnownColorObservation>> per_image;
  std::mutex per_image_mutex;
  ForEachImageWithMaps(model, scene, options.num_threads, "target images",
                       [&](const Image& image, const CameraRays& rays, const GeometryMaps& maps, int) {
    const cv::Mat observed = WithoutForwardScatter(ReadLinearImage(workspace.images_dir / image.name, options.input_encoding),
                                                   maps, rays, options.calibration.grid.forward_scatter,
                                                   sampling.saturation_level,
                                                   backscatter.For(maps, workspace.images_dir, image.name));
    const cv::Mat known = KnownAlbedoImage(targets, maps, rays, image.cam_from_world);
    std::vector<KnownColorObservation> observations = SampleKnownColors(observed, known, maps, rays, sampling);
    // In a survey most images show no target; in calibration images that is worth a warning.
    if (observations.empty() && !options.targets_workspace.empty()) {
      LogWarning() << image.name << ": no target pixels found; the image is skipped";
    }
    std::lock_guard<std::mutex> lock(per_image_mutex);
    per_image[image.image_id] = std::move(observations);
  });
  ObservationSet observations;
  for (auto& [id, list] : per_image) {
    for (KnownColorObservation& o : list) o.image = static_cast<int>(observations.images.size());
    observations.images.push_back(workspace.images_dir / model.images.at(id).name);
    observations.known_colors.insert(observations.known_colors.end(), list.begin(), list.end());
  }
  if (observations.known_colors.empty()) {
    throw std::runtime_error(options.targets.string() + ": no image of " + workspace.images_dir.string() +
                             " shows any target pixel");
  }
  return observations;
}

// The board of `path` (a chessboard or a ChArUco board, by the file's top-level key) as a function from
// an image to its maps, nothing where the board is not found; `what` names the board for messages.
std::function<std::optional<BoardMaps>(const cv::Mat&, const CameraRays&)> BoardFinder(const fs::path& path,
                                                                                           const Camera& camera,
                                                                                           std::string* what) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path.string() + ": no such board file");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error(path.string() + ": not a board file (" + JsonErrorText(error) + ")");
  }
  if (json.contains("charuco")) {
    const CharucoSpec spec = ReadCharucoSpec(path);
    *what = "ChArUco board of " + std::to_string(spec.squares_x) + " x " + std::to_string(spec.squares_y) + " squares";
    return [spec, camera](const cv::Mat& image, const CameraRays& rays) -> std::optional<BoardMaps> {
      const std::optional<BoardView> view = FindCharuco(image, camera, spec);
      if (!view) return std::nullopt;
      return RenderCharuco(spec, *view, rays);
    };
  }
  const ChessboardSpec spec = ReadChessboardSpec(path);
  *what = "chessboard of " + std::to_string(spec.inner_corners_x) + " x " + std::to_string(spec.inner_corners_y) +
          " inner corners";
  return [spec, camera](const cv::Mat& image, const CameraRays& rays) -> std::optional<BoardMaps> {
    const std::optional<BoardView> view = FindChessboard(image, camera, spec);
    if (!view) return std::nullopt;
    return RenderChessboard(spec, *view, rays, image);
  };
}

// Known colours from the board (chessboard or ChArUco) in every image of options.chessboard_images (sorted
// by name; images where OpenCV does not find it are skipped with a warning).
ObservationSet ChessboardObservations(const CalibrateOptions& options, const Camera& camera,
                                      const BackscatterSetAside& backscatter, CalibrateSummary* summary) {
  std::string board_name;
  const auto find_board = BoardFinder(options.chessboard, camera, &board_name);
  if (!fs::is_directory(options.chessboard_images)) {
    throw std::runtime_error(options.chessboard_images.string() + ": no such folder");
  }
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(options.chessboard_images)) {
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && (extension == ".png" || extension == ".jpg" || extension == ".jpeg" ||
                                    extension == ".tif" || extension == ".tiff" || extension == ".exr")) {
      paths.push_back(entry.path());
    }
  }
  std::sort(paths.begin(), paths.end());
  if (paths.empty()) throw std::runtime_error(options.chessboard_images.string() + ": no images");
  KnownColorSamplingOptions sampling = options.sampling;
  sampling.shading = options.calibration.grid.shading;
  const CameraRays rays(camera, options.num_threads);
  std::vector<std::vector<KnownColorObservation>> per_image(paths.size());
  ProgressReporter progress("board images", paths.size(), "images");
  ParallelFor(paths.size(), options.num_threads, [&](std::size_t i) {
    const cv::Mat image = ReadLinearImage(paths[i], options.input_encoding);
    if (image.cols != static_cast<int>(camera.width) || image.rows != static_cast<int>(camera.height)) {
      throw std::runtime_error(paths[i].string() + ": the image is " + std::to_string(image.cols) + "x" +
                               std::to_string(image.rows) + " but the camera is " + std::to_string(camera.width) + "x" +
                               std::to_string(camera.height));
    }
    const std::optional<BoardMaps> board = find_board(image, rays);
    if (!board) {
      LogWarning() << paths[i].string() << ": no " << board_name << " found; the image is skipped";
    } else {
      per_image[i] = SampleKnownColors(WithoutForwardScatter(image, board->maps, rays, options.calibration.grid.forward_scatter,
                                                             sampling.saturation_level,
                                                             backscatter.For(board->maps, paths[i].parent_path(),
                                                                             paths[i].filename().string())),
                                       board->known_albedo, board->maps, rays, sampling);
    }
    progress.Advance();
  });
  ObservationSet observations;
  for (std::size_t i = 0; i < per_image.size(); ++i) {
    summary->num_chessboard_images += per_image[i].empty() ? 0 : 1;
    for (KnownColorObservation& o : per_image[i]) o.image = static_cast<int>(observations.images.size());
    observations.images.push_back(paths[i]);
    observations.known_colors.insert(observations.known_colors.end(), per_image[i].begin(), per_image[i].end());
  }
  if (observations.known_colors.empty()) {
    throw std::runtime_error(options.chessboard_images.string() + ": the " + board_name + " of " +
                             options.chessboard.string() + " was found in none of the images");
  }
  return observations;
}

// Pure-water bounds from the images of options.pure_water, screened for surfaces in view (skipped with a
// warning naming the image and why).
ObservationSet PureWaterObservations(const CalibrateOptions& options, const Camera& camera,
                                     CalibrateSummary* summary) {
  const Workspace workspace = FindWorkspace(options.pure_water);
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  std::vector<std::vector<PureWaterObservation>> per_image;
  std::vector<PureWaterImageStats> stats;
  std::vector<fs::path> paths;
  for (const auto& [id, image] : model.images) {
    const Camera& water_camera = model.cameras.at(image.camera_id);
    paths.push_back(workspace.images_dir / image.name);
    if (water_camera.width != camera.width || water_camera.height != camera.height) {
      throw std::runtime_error(paths.back().string() + ": pure-water image of another size than the calibration images");
    }
    const cv::Mat observed = ReadLinearImage(paths.back(), options.input_encoding);
    stats.push_back(MeasurePureWaterImage(observed));
    per_image.push_back(SamplePureWater(observed, options.pure_water_stride));
  }
  const std::vector<std::string> reasons = ScreenPureWaterImages(stats, options.pure_water_screening);
  ObservationSet observations;
  for (std::size_t i = 0; i < per_image.size(); ++i) {
    if (!reasons[i].empty() && options.trust_pure_water) {
      LogWarning() << paths[i].string() << ": used as a pure-water image as --trust-pure-water says, although it seems "
                   << "to show a surface: " << reasons[i];
    } else if (!reasons[i].empty()) {
      LogWarning() << paths[i].string() << ": skipped as a pure-water image, it seems to show a surface: " << reasons[i]
                   << " (--trust-pure-water uses it anyway)";
      ++summary->num_pure_water_skipped;
      continue;
    }
    for (PureWaterObservation& o : per_image[i]) o.image = static_cast<int>(observations.images.size());
    observations.images.push_back(paths[i]);
    observations.pure_water.insert(observations.pure_water.end(), per_image[i].begin(), per_image[i].end());
    ++summary->num_pure_water_images;
  }
  if (observations.pure_water.empty()) {
    throw std::runtime_error(options.pure_water.string() +
                             ": none of its images looks like pure water (the warnings above say why; "
                             "--trust-pure-water uses them anyway)");
  }
  return observations;
}

// A LUT is for one image size: the separate target images must have the survey's.
void CheckSameImageSize(const Camera& targets_camera, const Camera& camera, const Workspace& targets_workspace) {
  if (targets_camera.width != camera.width || targets_camera.height != camera.height) {
    throw std::runtime_error(targets_workspace.sparse_dir.string() + ": the target images are " +
                             std::to_string(targets_camera.width) + "x" + std::to_string(targets_camera.height) +
                             " but the survey's are " + std::to_string(camera.width) + "x" +
                             std::to_string(camera.height) + "; a LUT is for one image size");
  }
}

// The calibration summary file beside the LUT: observation counts, residuals per constraint type,
// levels, histograms, time.
nlohmann::json Vector3Json(const Eigen::Vector3d& value) { return {value.x(), value.y(), value.z()}; }

// The fitted water (per channel r, g, b) and the rig it was rendered with.
nlohmann::json WaterPriorJson(const WaterPrior& prior) {
  return {{"in_air", prior.in_air},
          {"signal_attenuation_per_m", Vector3Json(prior.signal_attenuation)},
          {"backscatter_attenuation_per_m", Vector3Json(prior.backscatter_attenuation)},
          {"signal_scale", Vector3Json(prior.signal_scale)},
          {"backscatter_scale", Vector3Json(prior.backscatter_scale)},
          {"relative_rms", Vector3Json(prior.relative_rms)}};
}

// The fitted water and rig as a rig file (--shading-rig reads its "lights").
void WriteWaterPrior(const WaterPrior& prior, const std::filesystem::path& path) {
  nlohmann::json json = WaterPriorJson(prior);
  json["comment"] =
      "lutex calibrate: the water and rig fitted under the LUT (README, 'The water prior'). Only relative light "
      "intensities are meaningful. Usable as a --shading-rig file.";
  json["lights"] = LightRigToJson(prior.rig);
  WriteFileAtomically(path, std::ios::out, [&json](std::ostream& stream) { stream << json.dump(2) << "\n"; });
}

void WriteCalibrationSummary(const CalibrateSummary& summary, const CalibrationResult& result) {
  nlohmann::json json;
  json["known_color_observations"] = result.summary.num_known_color;
  json["pure_water_observations"] = result.summary.num_pure_water;
  json["known_color_rms"] = {result.summary.known_color_rms.x(), result.summary.known_color_rms.y(),
                             result.summary.known_color_rms.z()};
  json["pure_water_max_violation"] = {result.summary.pure_water_max_violation.x(),
                                      result.summary.pure_water_max_violation.y(),
                                      result.summary.pure_water_max_violation.z()};
  json["target_images"] = summary.num_target_images;
  json["chessboard_images"] = summary.num_chessboard_images;
  json["superpixel_samples"] = summary.num_superpixel_samples;
  json["correspondences"] = result.summary.num_correspondences;
  json["correspondence_albedo_rms"] = {result.summary.correspondence_albedo_rms.x(),
                                       result.summary.correspondence_albedo_rms.y(),
                                       result.summary.correspondence_albedo_rms.z()};
  json["pure_water_images"] = summary.num_pure_water_images;
  json["pure_water_images_skipped"] = summary.num_pure_water_skipped;
  json["covered_fraction"] = result.summary.covered_fraction;
  const RestoredObservationStats& restored = summary.restored_observations;
  json["restored_observations"] = {
      {"count", restored.count},
      {"judged_fraction", {restored.judged_fraction.x(), restored.judged_fraction.y(), restored.judged_fraction.z()}},
      {"implausible_fraction", {restored.implausible_fraction.x(), restored.implausible_fraction.y(),
                                restored.implausible_fraction.z()}},
      {"median_albedo", {restored.median_albedo.x(), restored.median_albedo.y(), restored.median_albedo.z()}}};
  if (summary.water_prior) json["water_prior"] = WaterPriorJson(*summary.water_prior);
  if (!summary.reference_water.empty()) {
    json["reference_water"] = {{"name", summary.reference_water},
                               {"chosen", summary.reference_water_reason}};
  }
  if (summary.measured_scattering) {
    json["forward_scatter"] = {{"measured_scattering", *summary.measured_scattering},
                               {"removed", summary.forward_scatter_asked},
                               {"taken_out", Vector3Json(summary.forward_scatter.scattering)},
                               {"anisotropy_g", summary.forward_scatter.anisotropy_g}};
  }
  if (summary.albedo_span.count > 0) {
    json["albedo_span"] = {{"lowest", Vector3Json(summary.albedo_span.lowest)},
                           {"highest", Vector3Json(summary.albedo_span.highest)}};
  }
  json["exposure"] = {{"exif_reference", summary.exposure.exif_reference},
                      {"exif_images", summary.num_exif_images},
                      {"fitted_gains", summary.exposure.fitted_gains}};
  json["warnings"] = summary.warnings;
  json["seconds"] = result.summary.seconds;
  for (const CalibrationLevelSummary& level : result.summary.levels) {
    json["levels"].push_back({{"nx", level.nx}, {"ny", level.ny},
                              {"iterations", {level.iterations[0], level.iterations[1], level.iterations[2]}},
                              {"final_cost", {level.final_cost[0], level.final_cost[1], level.final_cost[2]}}});
  }
  const auto histogram_json = [](const ResidualHistogram& histogram) {
    nlohmann::json entry;
    entry["range"] = histogram.range();
    for (int c = 0; c < 3; ++c) entry["counts"].push_back(histogram.counts(c));
    return entry;
  };
  json["residual_histograms"] = {
      {"known_color", histogram_json(result.summary.known_color_residuals)},
      {"correspondence_albedo_difference", histogram_json(result.summary.correspondence_albedo_differences)},
      {"pure_water_excess", histogram_json(result.summary.pure_water_excess)}};
  WriteFileAtomically(CalibrationSummaryPath(summary.lut), std::ios::out,
                      [&json](std::ostream& stream) { stream << json.dump(2) << "\n"; });
}

// Every observation the options ask for: known colours from the targets (in the workspace's images or
// separate ones) and the board, correspondences across the survey, pure-water bounds; with `backscatter`
// set aside where forward scattering is taken out.
ObservationSet GatherObservations(const CalibrateOptions& options, const LoadedDive& dive, const Camera& camera,
                                  const BackscatterSetAside& backscatter, CalibrateSummary* summary) {
  const Workspace& workspace = dive.workspace();
  const SparseModel& model = dive.model();
  ObservationSet observations;
  if (!options.targets.empty()) {
    const std::vector<Target> targets = ReadTargets(options.targets);
    if (!options.targets_workspace.empty()) {
      const Workspace targets_workspace = FindWorkspace(options.targets_workspace);
      const SparseModel targets_model = ReadSparseModel(targets_workspace.sparse_dir);
      const Mesh targets_mesh = ReadMesh(options.targets_mesh);
      CheckSameImageSize(SingleImageSize(targets_model, targets_workspace.sparse_dir), camera, targets_workspace);
      const RaycastScene targets_scene(targets_mesh);
      MergeObservations(
          KnownColorObservations(options, targets, targets_workspace, targets_model, targets_scene, backscatter),
          &observations);
      summary->num_target_images = targets_model.images.size();
    } else {
      MergeObservations(KnownColorObservations(options, targets, workspace, model, dive.scene(), backscatter),
                        &observations);
      summary->num_target_images = model.images.size();
    }
  }
  if (!options.chessboard.empty()) {
    MergeObservations(ChessboardObservations(options, camera, backscatter, summary), &observations);
  }
  if (options.correspondences) {
    SurveyCorrespondenceOptions extraction = options.correspondence_extraction;
    extraction.superpixels.shading = options.calibration.grid.shading;
    extraction.views.shading = options.calibration.grid.shading;
    extraction.input_encoding = options.input_encoding;
    extraction.forward_scatter = options.calibration.grid.forward_scatter;
    extraction.backscatter = backscatter;
    extraction.num_threads = options.num_threads;
    SurveyCorrespondences survey = ExtractSurveyCorrespondences(workspace.images_dir, model, dive.scene(), extraction);
    summary->num_superpixel_samples = survey.num_samples;
    if (survey.correspondences.empty()) {
      throw std::runtime_error(workspace.images_dir.string() +
                               ": no correspondences found (do the images overlap, and does the mesh cover them?)");
    }
    ObservationSet part;
    part.correspondences = std::move(survey.correspondences);
    part.images = std::move(survey.images);
    MergeObservations(std::move(part), &observations);
  }
  if (!options.pure_water.empty()) MergeObservations(PureWaterObservations(options, camera, summary), &observations);
  return observations;
}

// The rig shading assumes: the rig, or a point light at the one position.
LightRig ShadingRig(const CalibrateOptions& options) {
  LightRig rig = options.calibration.grid.shading.rig;
  if (rig.lights.empty()) {
    rig = PointLightAtCamera();
    rig.lights[0].position_in_cam = options.calibration.grid.shading.light_in_cam;
  }
  return rig;
}

// How the water prior is fitted: from the named water, the rig's beams too when no rig is given.
WaterPriorOptions WaterPriorOptionsOf(const CalibrateOptions& options) {
  WaterPriorOptions prior_options;
  prior_options.start = ReferenceWater(options);
  prior_options.grey_world_albedo = options.calibration.grey_world_albedo;
  prior_options.num_threads = options.num_threads;
  // In air the guess is a flash, and --shading-light says where it is.
  prior_options.fit_beam = options.calibration.grid.shading.rig.lights.empty() &&
                           !(options.calibration.in_air && !options.calibration.grid.shading.light_in_cam.isZero());
  return prior_options;
}

// The reference LUT (calibrator.h): the water prior fitted to the observations
// (lib/calibration/water_prior.h), starting from the named water, or in air the rig's light alone.
FrustumLut ReferenceLut(const CalibrateOptions& options, const Camera& camera, const FrustumLutGrid& grid,
                        const ObservationSet& observations, CalibrateSummary* summary) {
  summary->water_prior = FitWaterPrior(observations, ShadingRig(options), camera, grid, WaterPriorOptionsOf(options));
  return summary->water_prior->lut;
}

// Divides out of every observation its image's EXIF exposure (t * ISO / N^2 over the factors every
// calibration image has) relative to the median: the LUT is then for an image at the median exposure.
// Only the images that gave observations count (a board image where no board was found does not).
void DivideOutExifExposure(const CalibrateOptions& options, ObservationSet* observations, CalibrateSummary* summary) {
  std::vector<bool> observed(observations->images.size(), false);
  const auto mark = [&](int image) { if (image >= 0) observed[static_cast<std::size_t>(image)] = true; };
  for (const KnownColorObservation& o : observations->known_colors) mark(o.image);
  for (const PureWaterObservation& o : observations->pure_water) mark(o.image);
  for (const CorrespondenceObservation& o : observations->correspondences) {
    mark(o.first.image);
    mark(o.second.image);
  }
  std::vector<ExposureSettings> settings(observations->images.size());
  ParallelFor(settings.size(), options.num_threads, [&](std::size_t i) {
    if (observed[i]) settings[i] = ReadExposureSettings(observations->images[i]);
  });
  std::vector<ExposureSettings> used;
  std::size_t with_any = 0;
  const fs::path* first_without = nullptr;
  for (std::size_t i = 0; i < settings.size(); ++i) {
    if (!observed[i]) continue;
    used.push_back(settings[i]);
    const bool any = settings[i].exposure_time_s > 0.0 || settings[i].iso > 0.0 || settings[i].f_number > 0.0;
    with_any += any ? 1 : 0;
    if (!any && first_without == nullptr) first_without = &observations->images[i];
  }
  const ExposureFactors factors = FactorsInEvery(used);
  if (with_any > 0 && !factors.Any()) {
    LogWarning() << with_any << " of the " << used.size()
                 << " calibration images have exposure settings in EXIF, but no setting is in all of them"
                 << (first_without ? " (" + first_without->string() + " has none)" : std::string())
                 << "; EXIF exposure is not used";
  }
  if (!factors.Any()) return;
  std::vector<double> products;
  for (const ExposureSettings& s : settings) products.push_back(ExposureProduct(s, factors));
  std::vector<double> sorted;
  for (std::size_t i = 0; i < products.size(); ++i) {
    if (observed[i]) sorted.push_back(products[i]);
  }
  summary->exposure.exif_factors = factors;
  summary->exposure.exif_reference = MedianInPlace(sorted);
  summary->num_exif_images = used.size();
  // Images without observations are left at 1 (their product may be 0).
  for (std::size_t i = 0; i < products.size(); ++i) {
    products[i] = observed[i] ? products[i] / summary->exposure.exif_reference : 1.0;
  }
  DivideOutExposureGains(products, observations);
}

// The gains fitted for the workspace's own images, by their names in the model (the record restore reads).
void RecordFittedGains(const ExposureGains& gains, const ObservationSet& observations, const LoadedDive& dive,
                       CalibrateSummary* summary) {
  std::map<fs::path, std::size_t> index_of;
  for (std::size_t i = 0; i < observations.images.size(); ++i) index_of.emplace(observations.images[i], i);
  summary->exposure.fitted_images = fs::absolute(dive.workspace().images_dir).lexically_normal();
  for (const auto& [id, image] : dive.model().images) {
    const auto found = index_of.find(dive.workspace().images_dir / image.name);
    if (found != index_of.end() && gains.num_residuals[found->second] > 0) {
      summary->exposure.fitted_gains[image.name] = gains.gains[found->second];
    }
  }
}

}  // namespace

void CalibrateOptions::Check() const {
  if (workspace.empty() || mesh.empty()) throw OptionError("{workspace} and {mesh} are required");
  if (targets.empty() && chessboard.empty() && !correspondences) {
    throw OptionError(
        "give {targets} or {chessboard} (known colours), {correspondences} (self-calibration), or both");
  }
  if (chessboard.empty() != chessboard_images.empty()) {
    throw OptionError("{chessboard} and {chessboard_images} go together");
  }
  if (targets_workspace.empty() != targets_mesh.empty()) {
    throw OptionError("{targets_workspace} and {targets_mesh} go together");
  }
  if (!targets_workspace.empty() && targets.empty()) throw OptionError("{targets_workspace} needs {targets}");
  if (targets.empty() && chessboard.empty() && !(calibration.grey_world_albedo.minCoeff() > 0.0)) {
    throw OptionError(
        "without {targets}, correspondences fix the LUT only up to a factor per channel: give {targets} with one "
        "known colour, or {calibration.grey_world_albedo} (the mean albedo of the surveyed surfaces) to set the scale");
  }
  if (correspondences) correspondence_extraction.Check();
  if (reference_water != "auto" && !WaterPreset(reference_water)) {
    throw OptionError(std::string("{reference_water} must be auto, ") + WaterPresetNames() + ", not '" +
                      reference_water + "'");
  }
  if (pure_water_stride < 1) throw OptionError("{pure_water_stride} must be at least 1");
  if (exposure_gains != "auto" && exposure_gains != "fit" && exposure_gains != "none") {
    throw OptionError("{exposure_gains} must be auto, fit or none");
  }
  sampling.Check();
}

void AddCalibrationSources(const CalibrateOptions& options, InputsAndOutputs* paths) {
  paths->AddInput(options.targets, "the targets file");
  paths->AddInput(options.targets_workspace, "the targets' workspace");
  paths->AddInput(options.targets_mesh, "the targets' mesh");
  paths->AddInput(options.chessboard, "the board file");
  paths->AddInput(options.chessboard_images, "the board's images");
  paths->AddInput(options.pure_water, "the pure-water workspace");
  paths->AddInput(options.shading_rig, "the rig file");
}

namespace {

// What calibrate reads and writes (output_policy.h).
InputsAndOutputs PathsOf(const CalibrateOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(options.mesh, "the mesh");
  AddCalibrationSources(options, &paths);
  const fs::path lut = options.output.empty() ? workspace.LutPath() : options.output;
  for (const fs::path& output : {lut, CoverageLutPath(lut), CalibrationSummaryPath(lut), WaterPriorPath(lut),
                                ExposureRecordPath(lut), lut.parent_path() / "slabs"}) {
    paths.AddOutput(output);
  }
  return paths;
}

}  // namespace

CalibrateSummary CalibrateWorkspace(const CalibrateOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  return CalibrateWorkspace(options, LoadedDive(options.workspace, options.mesh));
}

CalibrateSummary CalibrateWorkspace(const CalibrateOptions& given, const LoadedDive& dive) {
  given.Check();
  const InputsAndOutputs paths = PathsOf(given, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  CheckStageMemory("calibrate", dive, given.num_threads, kImageStageBytesPerPixel, given.memory_limit_bytes);
  // The rig file, read once: its lights are the shading from here on.
  CalibrateOptions options = given;
  if (!options.shading_rig.empty()) options.calibration.grid.shading.rig = ReadLightRig(options.shading_rig);
  const Camera& camera = SingleImageSize(dive.model(), dive.workspace().sparse_dir);

  CalibrationOptions calibration = options.calibration;
  calibration.grid.image_width = static_cast<int>(camera.width);
  calibration.grid.image_height = static_cast<int>(camera.height);
  calibration.levels = DefaultLevels(calibration.grid.nx, calibration.grid.ny);
  calibration.num_threads = options.num_threads;
  calibration.Check();

  // Samples the observations (with `backscatter` set aside) and solves: the rig (fitted when asked, then
  // kept), the water prior, the LUT, the exposure gains.
  ObservationSet observations;
  const auto gather_and_solve = [&](const BackscatterSetAside& backscatter, CalibrateSummary* summary) {
    summary->num_images = dive.model().images.size();
    observations = GatherObservations(options, dive, camera, backscatter, summary);
    summary->num_observation_images = observations.images.size();
    DivideOutExifExposure(options, &observations, summary);
    // Not when the user said where the light is (a rig file, or --shading-light).
    if (options.fit_rig && calibration.grid.shading.rig.lights.empty() &&
        calibration.grid.shading.light_in_cam.isZero()) {
      // Shading with the fitted rig: fit it to the observations shaded from the camera, then shade them
      // with it (their cos_theta depends on the rig).
      const WaterPrior guess =
          FitWaterPrior(observations, ShadingRig(options), camera, calibration.grid, WaterPriorOptionsOf(options));
      LogInfo() << "shading with the fitted rig: " << DescribeWaterPrior(guess);
      options.calibration.grid.shading.rig = guess.rig;
      calibration.grid.shading.rig = guess.rig;
      Reshade(calibration.grid.shading,
              std::min(options.sampling.min_cos_theta, options.correspondence_extraction.views.min_cos_theta),
              &observations);
    }
    summary->albedo_span = SpanOfKnownColours(observations.known_colors);
    summary->warnings = NarrowSpanWarnings(summary->albedo_span, calibration.in_air, !observations.pure_water.empty(),
                                           !observations.correspondences.empty());
    LogInfo() << "calibrating from " << observations.known_colors.size() << " known-colour, "
              << observations.correspondences.size() << " correspondence and " << observations.pure_water.size()
              << " pure-water observations";
    const FrustumLut reference = ReferenceLut(options, camera, calibration.grid, observations, summary);
    const FrustumLut& reached = summary->water_prior->backscatter_reached;
    CalibrationResult solved = Calibrate(observations, reference, calibration, &reached);
    const bool fit_gains = !observations.correspondences.empty() &&
                           (options.exposure_gains == "fit" ||
                            (options.exposure_gains == "auto" && !observations.known_colors.empty()));
    if (fit_gains) {
      const ExposureGains gains = FitExposureGains(observations, solved.lut);
      RecordFittedGains(gains, observations, dive, summary);
      DivideOutExposureGains(gains.gains, &observations);
      LogInfo() << "calibrating again with the exposure gains divided out";
      solved = Calibrate(observations, reference, calibration, &reached);
    }
    return solved;
  };
  const bool in_water = !options.calibration.in_air;
  const bool measure_water = in_water && options.reference_water == "auto";
  if (measure_water) options.reference_water = "clear";  // the first fit starts from the clearest
  CalibrateSummary summary;
  CalibrationResult result = gather_and_solve(BackscatterSetAside{}, &summary);
  ForwardScatter scatter;
  std::optional<double> measured_scattering;
  std::string reference_water_reason = "given";
  bool fit_again = false;
  if (in_water) {
    measured_scattering = MeasuredScattering(*summary.water_prior);
    LogInfo() << "the water scatters about " << std::fixed << std::setprecision(3) << *measured_scattering
              << " per m (measured, forward_scatter_estimate.h)" << std::defaultfloat;
    if (measure_water && observations.known_colors.empty()) {
      // Without a known colour the fitted attenuations take up what the rig's guess gets wrong (simulated
      // clear water from correspondences: 0.49 per m for a b of 0.045), so the measurement names no water.
      reference_water_reason = "not measured without known colours";
      LogInfo() << "reference water: clear (without known colours the measurement is not trusted to name one)";
    } else if (measure_water) {
      reference_water_reason = "nearest the measurement";
      const std::string nearest = NearestWaterPreset(*measured_scattering);
      LogInfo() << "reference water: " << nearest << ", the preset nearest the measurement"
                << (nearest != options.reference_water ? "; fitting again from it" : "");
      fit_again = nearest != options.reference_water;
      options.reference_water = nearest;
    }
  }
  if (in_water && options.remove_forward_scatter) {
    scatter = ForwardScatterToTakeOut(*summary.water_prior, ReferenceWater(options));
    LogInfo() << "forward scattering: the " << options.reference_water << " water "
              << DescribeForwardScatter(ForwardScatter::Of(ReferenceWater(options)))
              << "; taking out the smaller of it and the measurement (forward_scatter_estimate.h)";
  }
  if (!scatter.IsNone()) {
    // From here on every image is sampled without it, and the LUT records it for restoration. It spreads
    // the light from the surfaces, not the backscatter, which the first LUT now estimates
    // (backscatter_set_aside.h).
    LogInfo() << "sampling again with " << DescribeForwardScatter(scatter)
              << " taken out and the first LUT's backscatter set aside";
    options.calibration.grid.forward_scatter = scatter;
    calibration.grid.forward_scatter = scatter;
    const CalibrationResult first = std::move(result);
    const CalibrateSummary first_summary = summary;
    summary = {};
    result = gather_and_solve(BackscatterSetAside{&first.lut, &first_summary.exposure}, &summary);
  } else if (fit_again) {
    summary = {};
    result = gather_and_solve(BackscatterSetAside{}, &summary);
  }
  if (in_water) {
    summary.reference_water = options.reference_water;
    summary.reference_water_reason = reference_water_reason;
  }
  summary.forward_scatter_asked = in_water && options.remove_forward_scatter;
  summary.forward_scatter = scatter;
  summary.measured_scattering = measured_scattering;
  for (const std::string& warning : summary.warnings) LogWarning() << warning;

  summary.restored_observations =
      RestoreObservations(result.lut, observations, summary.water_prior ? &summary.water_prior->lut : nullptr);
  CheckSolveIsPlausible(summary.restored_observations);
  summary.lut = options.output.empty() ? dive.workspace().LutPath() : options.output;
  summary.calibration = result.summary;
  WriteLut(result.lut, summary.lut);
  WriteLut(result.coverage, CoverageLutPath(summary.lut));
  WriteLutSlabImages(result.lut, summary.lut.parent_path() / "slabs");
  if (summary.water_prior) WriteWaterPrior(*summary.water_prior, WaterPriorPath(summary.lut));
  WriteExposureRecord(summary.exposure, ExposureRecordPath(summary.lut));
  WriteCalibrationSummary(summary, result);
  return summary;
}

namespace {

// One line on exposure: the EXIF factors used, and the range of the fitted gains.
std::string DescribeExposure(const CalibrateSummary& summary) {
  std::ostringstream text;
  const ExposureRecord& exposure = summary.exposure;
  if (exposure.exif_reference > 0.0) {
    text << "EXIF " << (exposure.exif_factors.exposure_time ? "t " : "") << (exposure.exif_factors.iso ? "ISO " : "")
         << (exposure.exif_factors.f_number ? "N " : "") << "of all " << summary.num_exif_images
         << " images, reference t*ISO/N^2 " << std::setprecision(4) << exposure.exif_reference;
  } else {
    text << "no EXIF exposure";
  }
  if (!exposure.fitted_gains.empty()) {
    double lowest = 1e300, highest = 0.0;
    for (const auto& [name, gain] : exposure.fitted_gains) {
      lowest = std::min(lowest, gain);
      highest = std::max(highest, gain);
    }
    text << "; gains fitted for " << exposure.fitted_gains.size() << " images, " << std::fixed << std::setprecision(3)
         << lowest << " to " << highest;
  }
  return text.str();
}

}  // namespace

void PrintCalibrateSummary(std::ostream& out, const CalibrateSummary& summary) {
  const CalibrationSummary& c = summary.calibration;
  out << std::fixed << std::setprecision(4) << "calibrate: " << summary.num_images << " images, "
            << c.num_known_color << " known-colour, " << c.num_correspondences << " correspondence and "
            << c.num_pure_water << " pure-water observations ("
            << summary.num_pure_water_images << " pure-water images, " << summary.num_pure_water_skipped
            << " skipped as showing a surface); "
            << "residual RMS " << c.known_color_rms.x() << " " << c.known_color_rms.y() << " " << c.known_color_rms.z()
            << "; correspondence albedo RMS " << c.correspondence_albedo_rms.x() << " " << c.correspondence_albedo_rms.y()
            << " " << c.correspondence_albedo_rms.z() << "; " << std::setprecision(0) << 100 * c.covered_fraction << " % of nodes covered; "
            << std::setprecision(1) << c.seconds << " s\n"
            << "  observations restored with the LUT: median albedo " << std::setprecision(3)
            << summary.restored_observations.median_albedo.x() << " " << summary.restored_observations.median_albedo.y()
            << " " << summary.restored_observations.median_albedo.z() << "; of those whose signal can pin their albedo ("
            << std::setprecision(0) << 100 * summary.restored_observations.judged_fraction.x() << " "
            << 100 * summary.restored_observations.judged_fraction.y() << " "
            << 100 * summary.restored_observations.judged_fraction.z() << " %), outside [-0.25, 1.5]: " << std::setprecision(1)
            << 100 * summary.restored_observations.implausible_fraction.x() << " "
            << 100 * summary.restored_observations.implausible_fraction.y() << " "
            << 100 * summary.restored_observations.implausible_fraction.z() << " %\n"
            << (summary.water_prior ? "  water prior: " + DescribeWaterPrior(*summary.water_prior) + "\n" : std::string());
  if (summary.measured_scattering) {
    out << "  water: measured to scatter about " << std::setprecision(3) << *summary.measured_scattering
        << " per m; reference " << summary.reference_water
        << " (" << summary.reference_water_reason << "); forward scattering "
        << (!summary.forward_scatter_asked ? std::string("kept (--no-remove-forward-scatter)")
            : summary.forward_scatter.IsNone() ? std::string("taken out: none")
                                               : "taken out: " + DescribeForwardScatter(summary.forward_scatter))
        << "\n";
  }
  out << "  exposure: " << DescribeExposure(summary) << "\n";
  for (const std::string& warning : summary.warnings) out << "  warning: " << warning << "\n";
  out << "  LUT:      " << summary.lut.string() << "\n"
      << "  coverage: " << CoverageLutPath(summary.lut).string() << "\n"
      << (summary.water_prior ? "  water:    " + WaterPriorPath(summary.lut).string() + "\n" : std::string())
      << "  exposure: " << ExposureRecordPath(summary.lut).string() << "\n";
}

}  // namespace lutex
