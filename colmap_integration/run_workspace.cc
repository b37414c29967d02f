#include "colmap_integration/run_workspace.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "colmap_integration/calibrate_command.h"
#include "colmap_integration/raycast_command.h"
#include "colmap_integration/report_workspace.h"
#include "colmap_integration/restore_command.h"
#include "colmap_integration/stage_record.h"
#include "colmap_integration/texture_command.h"
#include "colmap_integration/workspace.h"
#include "lib/util/atomic_output.h"
#include "lib/util/logging.h"

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

}  // namespace

void RunOptions::Check() const {
  if (workspace.empty()) throw std::invalid_argument("--workspace is required");
  if (mesh.empty()) throw std::invalid_argument("--mesh is required");
  if (lut.empty() && calibrate.targets.empty() && calibrate.chessboard.empty() && !calibrate.correspondences) {
    throw std::invalid_argument(
        "nothing to calibrate from: give --targets T or --chessboard C (known colours), --correspondences (with "
        "--grey-world V when there are no targets), or a LUT calibrated before with --lut L");
  }
}

RunSummary RunWorkspace(const RunOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const Workspace workspace = FindWorkspace(options.workspace);
  if (!fs::exists(options.mesh)) throw std::runtime_error(options.mesh.string() + ": no such mesh file");
  StageRunner runner(workspace.RunRecordsDir(), options.force);
  RunSummary summary;

  const auto base_record = [&](const std::string& stage) {
    StageRecord record(stage);
    AddSettings(&record, options);
    AddModel(&record, workspace);
    record.AddFile(options.mesh);
    return record;
  };

  if (options.raycast_maps) {
    RaycastOptions raycast = options.raycast;
    raycast.workspace = options.workspace;
    raycast.mesh = options.mesh;
    raycast.output = workspace.RaycastDir();
    raycast.num_threads = options.num_threads;
    StageRecord record = base_record("raycast");
    record.AddOutput(raycast.output);
    summary.stages.push_back(runner.Run(record, {raycast.output}, [&](bool resume) {
      raycast.skip_done = resume;
      return SummaryText(RaycastWorkspace(raycast), PrintRaycastSummary);
    }));
  }

  summary.lut = options.lut.empty() ? workspace.LutPath() : options.lut;
  if (options.lut.empty()) {
    CalibrateOptions calibrate = options.calibrate;
    calibrate.workspace = options.workspace;
    calibrate.mesh = options.mesh;
    calibrate.output = summary.lut;
    calibrate.input_encoding = options.input_encoding;
    calibrate.num_threads = options.num_threads;
    StageRecord record = base_record("calibrate");
    record.AddSetting("input-encoding", ImageEncodingName(options.input_encoding));
    AddFolder(&record, workspace.images_dir);
    if (!calibrate.targets.empty()) record.AddFile(calibrate.targets);
    if (!calibrate.targets_workspace.empty()) AddOtherWorkspace(&record, calibrate.targets_workspace);
    if (!calibrate.targets_mesh.empty()) record.AddFile(calibrate.targets_mesh);
    if (!calibrate.chessboard.empty()) record.AddFile(calibrate.chessboard);
    if (!calibrate.shading_rig.empty()) record.AddFile(calibrate.shading_rig);
    if (!calibrate.chessboard_images.empty()) AddFolder(&record, calibrate.chessboard_images);
    if (!calibrate.pure_water.empty()) AddOtherWorkspace(&record, calibrate.pure_water);
    record.AddOutput(summary.lut);
    record.AddOutput(CoverageLutPath(summary.lut));
    record.AddOutput(CalibrationSummaryPath(summary.lut));
    summary.stages.push_back(runner.Run(record, {summary.lut.parent_path()}, [&](bool) {
      return SummaryText(CalibrateWorkspace(calibrate), PrintCalibrateSummary);
    }));
  } else {
    summary.stages.push_back({"calibrate", "not needed", 0.0, "calibrate: LUT given: " + options.lut.string() + "\n"});
  }

  RestoreOptions restore = options.restore;
  restore.workspace = options.workspace;
  restore.mesh = options.mesh;
  restore.lut = summary.lut;
  restore.output = workspace.RestoredDir();
  restore.input_encoding = options.input_encoding;
  restore.num_threads = options.num_threads;
  summary.restored = restore.output;
  summary.confidence = ConfidenceDirOf(summary.restored);
  {
    StageRecord record = base_record("restore");
    record.AddSetting("input-encoding", ImageEncodingName(options.input_encoding));
    AddFolder(&record, workspace.images_dir);
    record.AddFileContents(summary.lut);
    const fs::path coverage = CoverageLutPath(summary.lut);
    if (!restore.ignore_coverage && fs::exists(coverage)) record.AddFileContents(coverage);
    record.AddOutput(summary.restored);
    record.AddOutput(summary.confidence);
    summary.stages.push_back(runner.Run(record, {summary.restored, summary.confidence}, [&](bool resume) {
      restore.skip_done = resume;
      return SummaryText(RestoreWorkspace(restore), PrintRestoreSummary);
    }));
  }

  TextureOptions texture = options.texture;
  texture.workspace = options.workspace;
  texture.mesh = options.mesh;
  texture.images = summary.restored;
  texture.confidence = summary.confidence;
  texture.image_encoding =
      restore.output_encoding == "same" ? options.input_encoding : ParseImageEncoding(restore.output_encoding);
  texture.output = workspace.ModelPath();
  texture.baking.num_threads = options.num_threads;
  summary.model = texture.output;
  {
    StageRecord record = base_record("texture");
    record.AddSetting("image-encoding", ImageEncodingName(texture.image_encoding));
    AddFolder(&record, summary.restored);
    if (!texture.ignore_confidence) AddFolder(&record, summary.confidence);
    record.AddOutput(texture.output);
    summary.stages.push_back(runner.Run(record, {texture.output.parent_path()}, [&](bool) {
      return SummaryText(TextureWorkspace(texture), PrintTextureSummary);
    }));
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (options.report) {
    ReportOptions report;
    report.workspace = options.workspace;
    report.lut = summary.lut;
    summary.report = WriteReport(report).index;
  }
  return summary;
}

}  // namespace lutex
