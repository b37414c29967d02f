#pragma once

// What one stage of `lutex run` consumed and produced, kept in W/lutex/run/STAGE.json so that a run started
// again skips what is still valid and resumes what was cut off:
//
//   {"stage": "restore", "state": "started" | "done", "fingerprint": "9f2c...",
//    "settings": {"output-encoding": "same", ...},            the options that shape the stage's output
//    "inputs": [{"path": ".../images/a.png", "size": 921654, "mtime_ns": 1763...}, ...
//               {"path": ".../lut.lut", "sha": "c0ffee..."}],   small derived files by content
//    "outputs": [".../restored", ...],
//    "seconds": 12.5, "summary": "restore: 24 images ..."}    (when done)
//
// The fingerprint is a 64-bit FNV-1a hash over the stage name, the settings and the inputs' identities.
// A stage whose record is "done" with the same fingerprint and whose outputs exist is skipped; one that is
// "started" with the same fingerprint was killed and resumes (per-image stages skip finished images).

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lutex {

struct StageInput {
  std::filesystem::path path;
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;
  std::string content_hash;  // hex; set for files identified by content instead of size and time
};

class StageRecord {
 public:
  explicit StageRecord(std::string stage) : stage_(std::move(stage)) {}

  // What shapes the output. Options that do not (threads, logging) stay out.
  void AddSetting(const std::string& name, const std::string& value) { settings_[name] = value; }
  // A file identified by size and modification time (images, models, meshes). Throws naming the file
  // when it does not exist.
  void AddFile(const std::filesystem::path& path);
  // A file identified by its contents (a LUT another stage wrote: redoing that stage with the same
  // result must not invalidate this one).
  void AddFileContents(const std::filesystem::path& path);
  void AddOutput(const std::filesystem::path& path) { outputs_.push_back(path); }

  std::string Fingerprint() const;
  bool OutputsExist() const;

  const std::string& stage() const { return stage_; }
  const std::map<std::string, std::string>& settings() const { return settings_; }
  const std::vector<StageInput>& inputs() const { return inputs_; }
  const std::vector<std::filesystem::path>& outputs() const { return outputs_; }

 private:
  std::string stage_;
  std::map<std::string, std::string> settings_;
  std::vector<StageInput> inputs_;
  std::vector<std::filesystem::path> outputs_;
};

struct StoredStageRecord {
  std::string state;  // "started" or "done"
  std::string fingerprint;
  double seconds = 0.0;
  std::string summary;
};

// Where the record of `stage` lives in a folder of records (W/lutex/run): STAGE.json.
std::filesystem::path StageRecordPath(const std::filesystem::path& records_dir, const std::string& stage);

// Writes `record` as `state` (temporary name, then rename).
void WriteStageRecord(const std::filesystem::path& path, const StageRecord& record, const std::string& state,
                      double seconds = 0.0, const std::string& summary = "");

// Empty when the file does not exist or cannot be parsed (a record is only a hint: without it the stage
// runs again).
std::optional<StoredStageRecord> ReadStageRecord(const std::filesystem::path& path);

}  // namespace lutex
