#include "colmap_integration/calibrate_workspace.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "colmap_integration/images_by_camera.h"
#include "colmap_integration/scene_description.h"
#include "colmap_integration/sparse_model_io.h"
#include "colmap_integration/survey_correspondences.h"
#include "colmap_integration/workspace.h"
#include "lib/calibration/charuco_target.h"
#include "lib/calibration/chessboard_target.h"
#include "lib/calibration/pure_water_sampling.h"
#include "lib/calibration/targets.h"
#include "lib/geometry/mesh_io.h"
#include "lib/lut/lut_file.h"
#include "lib/lut/lut_slab_images.h"
#include "lib/model/simulator.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/file_streams.h"
#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

Water ReferenceWater(const CalibrateOptions& options) {
  Water water;
  if (options.in_air) return water;
  if (options.reference_water == "clear") {
    water.absorption = Eigen::Vector3d(0.35, 0.05, 0.02);
    water.scattering = Eigen::Vector3d(0.04, 0.045, 0.05);
  } else {
    water.absorption = Eigen::Vector3d(0.45, 0.12, 0.25);
    water.scattering = Eigen::Vector3d(0.35, 0.4, 0.38);
  }
  water.anisotropy_g = 0.9;
  return water;
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
std::vector<KnownColorObservation> KnownColorObservations(const CalibrateOptions& options,
                                                          const std::vector<Target>& targets,
                                                          const Workspace& workspace, const SparseModel& model,
                                                          const RaycastScene& scene) {
  KnownColorSamplingOptions sampling = options.sampling;
  sampling.shading = options.shading;
  std::map<std::uint32_t, std::vector<KnownColorObservation>> per_image;
  std::mutex per_image_mutex;
  ForEachImageWithMaps(model, scene, options.num_threads, "target images",
                       [&](const Image& image, const CameraRays& rays, const GeometryMaps& maps, int) {
    const cv::Mat observed = ReadLinearImage(workspace.images_dir / image.name, options.input_encoding);
    const cv::Mat known = KnownAlbedoImage(targets, maps, rays, image.cam_from_world);
    std::vector<KnownColorObservation> observations = SampleKnownColors(observed, known, maps, rays, sampling);
    // In a survey most images show no target; in calibration images that is worth a warning.
    if (observations.empty() && !options.targets_workspace.empty()) {
      LogWarning() << image.name << ": no target pixels found; the image is skipped";
    }
    std::lock_guard<std::mutex> lock(per_image_mutex);
    per_image[image.image_id] = std::move(observations);
  });
  std::vector<KnownColorObservation> observations;
  for (auto& [id, list] : per_image) observations.insert(observations.end(), list.begin(), list.end());
  if (observations.empty()) {
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
    throw std::runtime_error(path.string() + ": not a board file (" + error.what() + ")");
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
std::vector<KnownColorObservation> ChessboardObservations(const CalibrateOptions& options, const Camera& camera,
                                                          CalibrateSummary* summary) {
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
  sampling.shading = options.shading;
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
      per_image[i] = SampleKnownColors(image, board->known_albedo, board->maps, rays, sampling);
    }
    progress.Advance();
  });
  std::vector<KnownColorObservation> observations;
  for (const auto& list : per_image) {
    summary->num_chessboard_images += list.empty() ? 0 : 1;
    observations.insert(observations.end(), list.begin(), list.end());
  }
  if (observations.empty()) {
    throw std::runtime_error(options.chessboard_images.string() + ": the " + board_name + " of " +
                             options.chessboard.string() + " was found in none of the images");
  }
  return observations;
}

// Pure-water bounds from the images of options.pure_water, screened for surfaces in view (skipped with a
// warning naming the image and why).
std::vector<PureWaterObservation> PureWaterObservations(const CalibrateOptions& options, const Camera& camera,
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
  std::vector<PureWaterObservation> observations;
  for (std::size_t i = 0; i < per_image.size(); ++i) {
    if (!reasons[i].empty()) {
      LogWarning() << paths[i].string() << ": skipped as a pure-water image, it seems to show a surface: " << reasons[i];
      ++summary->num_pure_water_skipped;
      continue;
    }
    observations.insert(observations.end(), per_image[i].begin(), per_image[i].end());
    ++summary->num_pure_water_images;
  }
  if (observations.empty()) {
    throw std::runtime_error(options.pure_water.string() + ": none of its images looks like pure water");
  }
  return observations;
}

}  // namespace

void CalibrateOptions::Check() const {
  if (workspace.empty() || mesh.empty()) throw std::invalid_argument("--workspace and --mesh are required");
  if (targets.empty() && chessboard.empty() && !correspondences) {
    throw std::invalid_argument(
        "give --targets or --chessboard (known colours), --correspondences (self-calibration), or both");
  }
  if (chessboard.empty() != chessboard_images.empty()) {
    throw std::invalid_argument("--chessboard and --chessboard-images go together");
  }
  if (targets_workspace.empty() != targets_mesh.empty()) {
    throw std::invalid_argument("--targets-workspace and --targets-mesh go together");
  }
  if (!targets_workspace.empty() && targets.empty()) throw std::invalid_argument("--targets-workspace needs --targets");
  if (targets.empty() && chessboard.empty() && !(grey_world_albedo.minCoeff() > 0.0)) {
    throw std::invalid_argument(
        "without --targets, correspondences fix the LUT only up to a factor per channel: give --targets with one "
        "known colour, or --grey-world V (the mean albedo of the surveyed surfaces) to set the scale");
  }
  if (correspondences) correspondence_extraction.Check();
  if (reference_water != "clear" && reference_water != "coastal") {
    throw std::invalid_argument("--reference-water must be clear or coastal");
  }
  if (pure_water_stride < 1) throw std::invalid_argument("the pure-water stride must be at least 1");
  sampling.Check();
}

CalibrateSummary CalibrateWorkspace(const CalibrateOptions& given) {
  given.Check();
  // The rig file, read once: its lights are the shading from here on.
  CalibrateOptions options = given;
  if (!options.shading_rig.empty()) options.shading.rig = ReadLightRig(options.shading_rig);
  const Workspace workspace = FindWorkspace(options.workspace);
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  const Camera& camera = SingleImageSize(model, workspace.sparse_dir);
  const std::vector<Target> targets = options.targets.empty() ? std::vector<Target>() : ReadTargets(options.targets);
  const Mesh mesh = ReadMesh(options.mesh);
  const RaycastScene scene(mesh);
  // Targets in separate calibration images, or in the workspace's own.
  const bool separate_targets = !options.targets_workspace.empty();
  const Workspace targets_workspace = separate_targets ? FindWorkspace(options.targets_workspace) : workspace;
  const SparseModel targets_model = separate_targets ? ReadSparseModel(targets_workspace.sparse_dir) : SparseModel();
  const Mesh targets_mesh = separate_targets ? ReadMesh(options.targets_mesh) : Mesh();
  if (separate_targets) {
    const Camera& targets_camera = SingleImageSize(targets_model, targets_workspace.sparse_dir);
    if (targets_camera.width != camera.width || targets_camera.height != camera.height) {
      throw std::runtime_error(targets_workspace.sparse_dir.string() + ": the target images are " +
                               std::to_string(targets_camera.width) + "x" + std::to_string(targets_camera.height) +
                               " but the survey's are " + std::to_string(camera.width) + "x" +
                               std::to_string(camera.height) + "; a LUT is for one image size");
    }
  }

  CalibrationOptions calibration = options.calibration;
  calibration.grid.nx = options.nx;
  calibration.grid.ny = options.ny;
  calibration.grid.nz = options.nz;
  calibration.grid.z_near = options.z_near;
  calibration.grid.z_far = options.z_far;
  calibration.grid.image_width = static_cast<int>(camera.width);
  calibration.grid.image_height = static_cast<int>(camera.height);
  calibration.grid.shading = options.shading;
  calibration.levels = DefaultLevels(options.nx, options.ny);
  calibration.in_air = options.in_air;
  calibration.num_threads = options.num_threads;
  calibration.grey_world_albedo = options.grey_world_albedo;
  calibration.Check();

  CalibrateSummary summary;
  summary.num_images = model.images.size();
  ObservationSet observations;
  if (!targets.empty()) {
    if (separate_targets) {
      const RaycastScene targets_scene(targets_mesh);
      observations.known_colors = KnownColorObservations(options, targets, targets_workspace, targets_model, targets_scene);
      summary.num_target_images = targets_model.images.size();
    } else {
      observations.known_colors = KnownColorObservations(options, targets, workspace, model, scene);
      summary.num_target_images = model.images.size();
    }
  }
  if (!options.chessboard.empty()) {
    const std::vector<KnownColorObservation> board = ChessboardObservations(options, camera, &summary);
    observations.known_colors.insert(observations.known_colors.end(), board.begin(), board.end());
  }
  if (options.correspondences) {
    SurveyCorrespondenceOptions extraction = options.correspondence_extraction;
    extraction.superpixels.shading = options.shading;
    extraction.views.shading = options.shading;
    extraction.input_encoding = options.input_encoding;
    extraction.num_threads = options.num_threads;
    const SurveyCorrespondences survey = ExtractSurveyCorrespondences(workspace, model, scene, extraction);
    observations.correspondences = survey.correspondences;
    summary.num_superpixel_samples = survey.num_samples;
    if (observations.correspondences.empty()) {
      throw std::runtime_error(workspace.images_dir.string() +
                               ": no correspondences found (do the images overlap, and does the mesh cover them?)");
    }
  }
  if (!options.pure_water.empty()) {
    observations.pure_water = PureWaterObservations(options, camera, &summary);
  }
  LogInfo() << "calibrating from " << observations.known_colors.size() << " known-colour, "
            << observations.correspondences.size() << " correspondence and " << observations.pure_water.size()
            << " pure-water observations";

  const Mesh no_geometry;
  // The reference lights are where shading assumes them: the rig, or a point light at the one position.
  LightRig reference_rig = options.shading.rig;
  if (reference_rig.lights.empty()) {
    reference_rig = PointLightAtCamera();
    reference_rig.lights[0].position_in_cam = options.shading.light_in_cam;
  }
  const Simulator reference_simulator(no_geometry, reference_rig, ReferenceWater(options),
                                      SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  const CalibrationResult result =
      Calibrate(observations, reference_simulator.TrueLut(camera, calibration.grid), calibration);

  summary.lut = options.output.empty() ? workspace.LutPath() : options.output;
  summary.calibration = result.summary;
  WriteLut(result.lut, summary.lut);
  WriteLut(result.coverage, CoverageLutPath(summary.lut));
  WriteLutSlabImages(result.lut, summary.lut.parent_path() / "slabs");
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
  return summary;
}

}  // namespace lutex
