#include "colmap_integration/stages/run_workspace.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/report_workspace.h"
#include "colmap_integration/stages/stage_record.h"
#include "lib/util/atomic_output.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

// Every regular file under `folder`, sorted, without the temporaries of writers (dot files).
void AddFolder(StageRecord* record, const fs::path& folder) {
  if (!fs::is_directory(folder)) throw std::runtime_error(folder.string() + ": no such folder");
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().filename().string().front() != '.') files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) record->AddFile(file);
}

// The sparse model's files (one level: cameras, images, points3D, in any format).
void AddModel(StageRecord* record, const Workspace& workspace) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(workspace.sparse_dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) record->AddFile(file);
}

// A second workspace a stage reads (calibration images, pure water): its model and images.
void AddOtherWorkspace(StageRecord* record, const fs::path& root) {
  const Workspace other = FindWorkspace(root);
  AddModel(record, other);
  AddFolder(record, other.images_dir);
}

void AddSettings(StageRecord* record, const RunOptions& options) {
  const auto found = options.stage_settings.find(record->stage());
  if (found == options.stage_settings.end()) return;
  for (const auto& [name, value] : found->second) record->AddSetting(name, value);
}

class StageRunner {
 public:
  StageRunner(fs::path records_dir, bool force) : records_dir_(std::move(records_dir)), force_(force) {}

  // Runs `work(resume)` unless `record` is up to date; `work` returns the stage's summary lines.
  // `output_folders` are cleared of a killed run's temporaries first.
  RunStageSummary Run(const StageRecord& record, const std::vector<fs::path>& output_folders,
                      const std::function<std::string(bool resume)>& work) {
    const fs::path record_path = StageRecordPath(records_dir_, record.stage());
    const std::string fingerprint = record.Fingerprint();
    const std::optional<StoredStageRecord> previous = ReadStageRecord(record_path);
    RunStageSummary stage;
    stage.stage = record.stage();
    if (!force_ && previous && previous->fingerprint == fingerprint && previous->state == "done" &&
        record.OutputsExist()) {
      LogInfo() << record.stage() << ": up to date (" << record_path.string() << ")";
      stage.status = "up to date";
      stage.seconds = previous->seconds;
      stage.summary = previous->summary;
      return stage;
    }
    const bool resume = !force_ && previous && previous->fingerprint == fingerprint;
    for (const fs::path& folder : output_folders) {
      if (const std::size_t removed = RemoveStaleTemporaries(folder)) {
        LogInfo() << record.stage() << ": removed " << removed << " unfinished file(s) of an interrupted run in "
                  << folder.string();
      }
    }
    LogInfo() << record.stage() << ": " << (resume ? "resuming an interrupted run" : "running");
    WriteStageRecord(record_path, record, "started");
    const auto start = std::chrono::steady_clock::now();
    stage.summary = work(resume);
    stage.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stage.status = resume ? "resumed" : "done";
    WriteStageRecord(record_path, record, "done", stage.seconds, stage.summary);
    return stage;
  }

 private:
  fs::path records_dir_;
  bool force_;
};

template <typename Summary, typename Print>
std::string SummaryText(const Summary& summary, Print print) {
  std::ostringstream text;
  print(text, summary);
  return text.str();
}

// One `lutex run`: its options, the workspace, the stage runner and the summary so far; one method per stage.
class DiveRun {
 public:
  explicit DiveRun(const RunOptions& options)
      : options_(options), workspace_(FindWorkspace(options.workspace)),
        runner_(workspace_.RunRecordsDir(), options.force), mesh_(options.mesh) {}

  // Without --mesh: a dense workspace's own mesh, else one from the sparse model (lutex mesh).
  void Mesh() {
    if (!mesh_.empty()) return;
    const fs::path dense = DenseMeshOf(workspace_);
    if (!dense.empty()) {
      mesh_ = dense;
      summary_.stages.push_back({"mesh", "not needed", 0.0, "mesh: the dense workspace's own, " + dense.string() + "\n"});
      summary_.mesh = mesh_;
      return;
    }
    MeshOptions mesh = options_.mesh_options;
    mesh.workspace = options_.workspace;
    mesh.output = workspace_.MeshPath();
    mesh.georeference = options_.mosaic.georeference;
    StageRecord record("mesh");
    AddSettings(&record, options_);
    record.AddSetting("georeference", ResolveGeoreference(mesh.georeference, workspace_).georeference.Describe());
    AddModel(&record, workspace_);
    if (fs::exists(workspace_.GeoreferencePath())) record.AddFileContents(workspace_.GeoreferencePath());
    record.AddOutput(mesh.output);
    summary_.stages.push_back(runner_.Run(record, {mesh.output.parent_path()}, [&](bool) {
      return SummaryText(MeshWorkspace(mesh), PrintMeshSummary);
    }));
    mesh_ = mesh.output;
    summary_.mesh = mesh_;
  }

  // With depth_maps only: COLMAP depth and normal maps in W/lutex/raycast.
  void Raycast() {
    RaycastOptions raycast = options_.raycast;
    raycast.workspace = options_.workspace;
    raycast.mesh = mesh_;
    raycast.output = workspace_.RaycastDir();
    raycast.num_threads = options_.num_threads;
    raycast.memory_limit_bytes = options_.memory_limit_bytes;
    StageRecord record = BaseRecord("raycast");
    record.AddOutput(raycast.output);
    summary_.stages.push_back(runner_.Run(record, {raycast.output}, [&](bool resume) {
      raycast.skip_done = resume;
      return SummaryText(RaycastWorkspace(raycast, Dive()), PrintRaycastSummary);
    }));
  }

  // The LUT: calibrated, or the one given.
  void Calibrate() {
    summary_.lut = options_.lut.empty() ? workspace_.LutPath() : options_.lut;
    if (options_.lut.empty()) {
      CalibrateOptions calibrate = options_.calibrate;
      calibrate.workspace = options_.workspace;
      calibrate.mesh = mesh_;
      calibrate.output = summary_.lut;
      calibrate.input_encoding = options_.input_encoding;
      calibrate.num_threads = options_.num_threads;
      calibrate.memory_limit_bytes = options_.memory_limit_bytes;
      StageRecord record = BaseRecord("calibrate");
      record.AddSetting("input-encoding", ImageEncodingName(options_.input_encoding));
      AddFolder(&record, workspace_.images_dir);
      if (!calibrate.targets.empty()) record.AddFile(calibrate.targets);
      if (!calibrate.targets_workspace.empty()) AddOtherWorkspace(&record, calibrate.targets_workspace);
      if (!calibrate.targets_mesh.empty()) record.AddFile(calibrate.targets_mesh);
      if (!calibrate.chessboard.empty()) record.AddFile(calibrate.chessboard);
      if (!calibrate.shading_rig.empty()) record.AddFile(calibrate.shading_rig);
      if (!calibrate.chessboard_images.empty()) AddFolder(&record, calibrate.chessboard_images);
      if (!calibrate.pure_water.empty()) AddOtherWorkspace(&record, calibrate.pure_water);
      record.AddOutput(summary_.lut);
      record.AddOutput(CoverageLutPath(summary_.lut));
      record.AddOutput(CalibrationSummaryPath(summary_.lut));
      record.AddOutput(ExposureRecordPath(summary_.lut));
      summary_.stages.push_back(runner_.Run(record, {summary_.lut.parent_path()}, [&](bool) {
        return SummaryText(CalibrateWorkspace(calibrate, Dive()), PrintCalibrateSummary);
      }));
    } else {
      summary_.stages.push_back({"calibrate", "not needed", 0.0, "calibrate: LUT given: " + options_.lut.string() + "\n"});
    }
  }

  // Every image to albedo, with confidence maps.
  void Restore() {
    RestoreOptions restore = options_.restore;
    restore.workspace = options_.workspace;
    restore.mesh = mesh_;
    restore.lut = summary_.lut;
    restore.output = workspace_.RestoredDir();
    restore.input_encoding = options_.input_encoding;
    restore.num_threads = options_.num_threads;
    restore.memory_limit_bytes = options_.memory_limit_bytes;
    summary_.restored = restore.output;
    summary_.confidence = ConfidenceDirOf(summary_.restored);
    StageRecord record = BaseRecord("restore");
    record.AddSetting("input-encoding", ImageEncodingName(options_.input_encoding));
    AddFolder(&record, workspace_.images_dir);
    record.AddFileContents(summary_.lut);
    const fs::path coverage = CoverageLutPath(summary_.lut);
    if (!restore.ignore_coverage && fs::exists(coverage)) record.AddFileContents(coverage);
    if (fs::exists(ExposureRecordPath(summary_.lut))) record.AddFileContents(ExposureRecordPath(summary_.lut));
    record.AddOutput(summary_.restored);
    record.AddOutput(summary_.confidence);
    summary_.stages.push_back(runner_.Run(record, {summary_.restored, summary_.confidence}, [&](bool resume) {
      restore.skip_done = resume;
      return SummaryText(RestoreWorkspace(restore, Dive()), PrintRestoreSummary);
    }));
  }

  // The albedo texture of the mesh, from the restored images.
  void Texture() {
    TextureOptions texture = options_.texture;
    texture.workspace = options_.workspace;
    texture.mesh = mesh_;
    texture.views = TextureViews();
    texture.georeference = options_.mosaic.georeference;
    texture.output = workspace_.ModelPath();
    texture.baking.num_threads = options_.num_threads;
    texture.memory_limit_bytes = options_.memory_limit_bytes;
    summary_.model = texture.output;
    StageRecord record = BaseRecord("texture");
    record.AddSetting("image-encoding", ImageEncodingName(texture.views.image_encoding));
    record.AddSetting("georeference", ResolveGeoreference(texture.georeference, workspace_).georeference.Describe());
    AddFolder(&record, summary_.restored);
    if (!texture.views.ignore_confidence) AddFolder(&record, summary_.confidence);
    record.AddOutput(texture.output);
    summary_.stages.push_back(runner_.Run(record, {texture.output.parent_path()}, [&](bool) {
      return SummaryText(TextureWorkspace(texture, Dive()), PrintTextureSummary);
    }));
  }

  // The orthomosaic and DEM, from the restored images, with the texture's view selection and fusion.
  void Mosaic() {
    MosaicOptions mosaic = options_.mosaic;
    mosaic.workspace = options_.workspace;
    mosaic.mesh = mesh_;
    mosaic.views = TextureViews();
    mosaic.output = workspace_.OrthomosaicPath();
    mosaic.dem = workspace_.DemPath();
    mosaic.ortho.baking = options_.texture.baking;
    mosaic.ortho.baking.num_threads = options_.num_threads;
    mosaic.memory_limit_bytes = options_.memory_limit_bytes;
    const WorkspaceGeoreference georeference = ResolveGeoreference(mosaic.georeference, workspace_);
    if (!georeference.georeference.IsSet()) {
      const std::string unfit = WhyNotAMapWithoutGeoreference(Dive().model());
      if (!unfit.empty()) {
        summary_.stages.push_back({"mosaic", "not needed", 0.0, "mosaic: skipped: " + unfit + "\n"});
        return;
      }
    }
    summary_.mosaic = mosaic.output;
    StageRecord record = BaseRecord("mosaic");
    for (const auto& [name, value] : TextureSettings()) record.AddSetting("texture " + name, value);
    record.AddSetting("image-encoding", ImageEncodingName(mosaic.views.image_encoding));
    AddFolder(&record, summary_.restored);
    if (!mosaic.views.ignore_confidence) AddFolder(&record, summary_.confidence);
    if (fs::exists(workspace_.GeoreferencePath())) record.AddFileContents(workspace_.GeoreferencePath());
    record.AddOutput(mosaic.output);
    record.AddOutput(mosaic.dem);
    summary_.stages.push_back(runner_.Run(record, {mosaic.output.parent_path()}, [&](bool) {
      return SummaryText(MosaicWorkspace(mosaic, Dive()), PrintMosaicSummary);
    }));
  }

  // The 3D Tiles, from the restored images, with the texture's view selection and fusion; only for a
  // georeferenced model (tiles that do not sit on the globe are of no use to a map viewer).
  void Tiles() {
    TilesOptions tiles = options_.tiles;
    tiles.workspace = options_.workspace;
    tiles.mesh = mesh_;
    tiles.views = TextureViews();
    tiles.georeference = options_.mosaic.georeference;
    tiles.output = workspace_.TilesDir();
    tiles.baking = options_.texture.baking;
    tiles.baking.num_threads = options_.num_threads;
    tiles.up_axis = options_.texture.up_axis;
    tiles.gltf = options_.texture.gltf;
    tiles.memory_limit_bytes = options_.memory_limit_bytes;
    const WorkspaceGeoreference georeference = ResolveGeoreference(tiles.georeference, workspace_);
    if (!georeference.georeference.IsSet()) {
      summary_.stages.push_back({"tiles", "not needed", 0.0,
                                 "tiles: skipped: the model is not georeferenced (no --crs or --enu-origin, no " +
                                     workspace_.GeoreferencePath().string() + "), so 3D Tiles would not sit on the globe\n"});
      return;
    }
    summary_.tileset = tiles.output / "tileset.json";
    StageRecord record = BaseRecord("tiles");
    for (const auto& [name, value] : TextureSettings()) record.AddSetting("texture " + name, value);
    record.AddSetting("image-encoding", ImageEncodingName(tiles.views.image_encoding));
    record.AddSetting("georeference", georeference.georeference.Describe());
    AddFolder(&record, summary_.restored);
    if (!tiles.views.ignore_confidence) AddFolder(&record, summary_.confidence);
    record.AddOutput(summary_.tileset);
    summary_.stages.push_back(runner_.Run(record, {tiles.output.parent_path()}, [&](bool) {
      return SummaryText(TilesWorkspace(tiles, Dive()), PrintTilesSummary);
    }));
  }

  void Report() {
    ReportOptions report;
    report.workspace = options_.workspace;
    report.lut = summary_.lut;
    summary_.report = WriteReport(report).index;
  }

  const Workspace& workspace() const { return workspace_; }
  RunSummary& summary() { return summary_; }

 private:
  // The restored images and their confidence, as restore wrote them, with the texture's confidence choice.
  WorkspaceViewsOptions TextureViews() const {
    WorkspaceViewsOptions views = options_.texture.views;
    views.images = summary_.restored;
    views.confidence = summary_.confidence;
    views.image_encoding = options_.restore.output_encoding == "same"
                               ? options_.input_encoding
                               : ParseImageEncoding(options_.restore.output_encoding);
    return views;
  }

  std::map<std::string, std::string> TextureSettings() const {
    const auto found = options_.stage_settings.find("texture");
    return found == options_.stage_settings.end() ? std::map<std::string, std::string>() : found->second;
  }

  // The record every stage starts from: its settings, the model and the mesh.
  StageRecord BaseRecord(const std::string& stage) const {
    StageRecord record(stage);
    AddSettings(&record, options_);
    AddModel(&record, workspace_);
    record.AddFile(mesh_);
    return record;
  }

  // The model, mesh and ray-casting scene, loaded by the first stage that runs and shared by the others
  // (loaded again after a stage that released the mesh).
  LoadedDive& Dive() {
    if (!loaded_ || !loaded_->has_mesh()) loaded_ = std::make_unique<LoadedDive>(options_.workspace, mesh_);
    return *loaded_;
  }

  const RunOptions& options_;
  const Workspace workspace_;
  StageRunner runner_;
  RunSummary summary_;
  std::unique_ptr<LoadedDive> loaded_;
  fs::path mesh_;  // --mesh, or the one the mesh stage found or made
};

// What the whole run reads and writes (output_policy.h), checked before the first stage starts: the stages
// check their own again, but a late stage's refusal must not come after an early stage has written.
InputsAndOutputs RunPaths(const RunOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(options.mesh, "the mesh");
  if (options.mesh.empty()) paths.AddOutput(workspace.MeshPath());
  paths.AddInput(options.lut, "the LUT");
  AddCalibrationSources(options.calibrate, &paths);
  paths.AddOutput(workspace.RunRecordsDir());
  if (options.raycast_maps) paths.AddOutput(workspace.RaycastDir());
  if (options.lut.empty()) paths.AddOutput(workspace.LutPath().parent_path());
  paths.AddOutput(workspace.RestoredDir());
  paths.AddOutput(ConfidenceDirOf(workspace.RestoredDir()));
  paths.AddOutput(workspace.ModelPath());
  if (options.make_mosaic) {
    paths.AddInput(workspace.GeoreferencePath(), "the georeference file");
    paths.AddOutput(workspace.OrthomosaicPath());
    paths.AddOutput(workspace.DemPath());
  }
  if (options.make_tiles) {
    paths.AddInput(workspace.GeoreferencePath(), "the georeference file");
    paths.AddOutput(workspace.TilesDir());
  }
  if (options.report) paths.AddOutput(workspace.ReportDir());
  return paths;
}

}  // namespace

void RunOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (lut.empty() && calibrate.targets.empty() && calibrate.chessboard.empty() && !calibrate.correspondences) {
    throw OptionError(
        "nothing to calibrate from: give {targets} or {chessboard} (known colours), {correspondences} (with "
        "{grey_world_albedo} when there are no targets), or a LUT calibrated before with {lut}");
  }
}

RunSummary RunWorkspace(const RunOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  DiveRun run(options);
  if (!options.mesh.empty() && !fs::exists(options.mesh)) {
    throw std::runtime_error(options.mesh.string() + ": no such mesh file");
  }
  RunPaths(options, run.workspace()).Check();
  // One writer per workspace: a second run would take the first one's records for an interrupted run.
  const ExclusiveFileLock lock(WorkspaceLockPath(run.workspace()), run.workspace().root.string());
  run.Mesh();
  if (options.raycast_maps) run.Raycast();
  run.Calibrate();
  run.Restore();
  run.Texture();
  if (options.make_mosaic) run.Mosaic();
  if (options.make_tiles) run.Tiles();
  run.summary().seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.report) run.Report();
  return run.summary();
}

}  // namespace lutex
