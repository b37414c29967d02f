#include "colmap_integration/stages/stage_record.h"

#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lib/util/file_streams.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

void HashBytes(std::uint64_t* hash, const char* bytes, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    *hash ^= static_cast<unsigned char>(bytes[i]);
    *hash *= kFnvPrime;
  }
}

// Strings are hashed with their length so that ("ab", "c") and ("a", "bc") differ.
void HashString(std::uint64_t* hash, const std::string& text) {
  const std::uint64_t length = text.size();
  HashBytes(hash, reinterpret_cast<const char*>(&length), sizeof(length));
  HashBytes(hash, text.data(), text.size());
}

std::string Hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << value;
  return out.str();
}

}  // namespace

void StageRecord::AddFile(const fs::path& path) {
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) throw std::runtime_error(path.string() + ": cannot read (" + error.message() + ")");
  const auto mtime = fs::last_write_time(path);
  StageInput input;
  input.path = path;
  input.size = size;
  input.mtime_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(mtime.time_since_epoch()).count();
  inputs_.push_back(input);
}

void StageRecord::AddFileContents(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(path.string() + ": cannot read");
  std::uint64_t hash = kFnvOffset;
  std::vector<char> buffer(1 << 16);
  while (file) {
    file.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    HashBytes(&hash, buffer.data(), static_cast<std::size_t>(file.gcount()));
  }
  StageInput input;
  input.path = path;
  input.content_hash = Hex(hash);
  inputs_.push_back(input);
}

std::string StageRecord::Fingerprint() const {
  std::uint64_t hash = kFnvOffset;
  HashString(&hash, stage_);
  for (const auto& [name, value] : settings_) {
    HashString(&hash, name);
    HashString(&hash, value);
  }
  for (const StageInput& input : inputs_) {
    HashString(&hash, input.path.string());
    HashString(&hash, input.content_hash.empty() ? std::to_string(input.size) + "@" + std::to_string(input.mtime_ns)
                                                 : input.content_hash);
  }
  return Hex(hash);
}

bool StageRecord::OutputsExist() const {
  for (const fs::path& output : outputs_) {
    if (!fs::exists(output)) return false;
  }
  return true;
}

fs::path StageRecordPath(const fs::path& records_dir, const std::string& stage) {
  return records_dir / (stage + ".json");
}

void WriteStageRecord(const fs::path& path, const StageRecord& record, const std::string& state, double seconds,
                      const std::string& summary) {
  nlohmann::ordered_json json;
  json["stage"] = record.stage();
  json["state"] = state;
  json["fingerprint"] = record.Fingerprint();
  json["settings"] = record.settings();
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const StageInput& input : record.inputs()) {
    nlohmann::ordered_json entry;
    entry["path"] = input.path.string();
    if (input.content_hash.empty()) {
      entry["size"] = input.size;
      entry["mtime_ns"] = input.mtime_ns;
    } else {
      entry["sha"] = input.content_hash;
    }
    inputs.push_back(entry);
  }
  json["inputs"] = inputs;
  nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
  for (const fs::path& output : record.outputs()) outputs.push_back(output.string());
  json["outputs"] = outputs;
  if (state == "done") {
    json["seconds"] = seconds;
    json["summary"] = summary;
  }
  WriteFileAtomically(path, std::ios::out, [&](std::ostream& out) { out << json.dump(1) << "\n"; });
}

std::optional<StoredStageRecord> ReadStageRecord(const fs::path& path) {
  std::ifstream file(path);
  if (!file) return std::nullopt;
  try {
    const nlohmann::json json = nlohmann::json::parse(file);
    StoredStageRecord stored;
    stored.state = json.at("state").get<std::string>();
    stored.fingerprint = json.at("fingerprint").get<std::string>();
    if (json.contains("seconds")) stored.seconds = json.at("seconds").get<double>();
    if (json.contains("summary")) stored.summary = json.at("summary").get<std::string>();
    return stored;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace lutex
