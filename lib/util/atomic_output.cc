#include "lib/util/atomic_output.h"

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace lutex {
namespace {

std::atomic<unsigned> g_counter{0};

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::filesystem::path destination)
    : destination_(std::move(destination)) {
  if (destination_.has_parent_path()) std::filesystem::create_directories(destination_.parent_path());
  // The temporary keeps the destination's extension so that writers choosing a format by extension
  // (OpenCV's imwrite) still see it.
  temporary_path_ = destination_;
  temporary_path_.replace_filename("." + destination_.stem().string() + ".tmp" +
                                   std::to_string(getpid()) + "_" + std::to_string(g_counter++) +
                                   destination_.extension().string());
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(temporary_path_, ignored);
  }
}

void AtomicOutputFile::Commit() {
  if (!std::filesystem::exists(temporary_path_)) {
    throw std::runtime_error(destination_.string() + ": nothing was written");
  }
  if (std::filesystem::is_directory(temporary_path_) && std::filesystem::is_directory(destination_)) {
    // A folder cannot be renamed over a folder that holds files: the old one is moved aside first.
    const std::filesystem::path old = temporary_path_.string() + ".old";
    std::filesystem::rename(destination_, old);
    std::filesystem::rename(temporary_path_, destination_);
    committed_ = true;
    std::error_code ignored;
    std::filesystem::remove_all(old, ignored);
    return;
  }
  std::filesystem::rename(temporary_path_, destination_);
  committed_ = true;
}

bool IsStaleTemporary(const std::filesystem::path& path) {
  // ".STEM.tmpPID_N.EXT", possibly with what a library writing it adds after (GDAL's ".ovr.tmp"): the
  // writer's process id follows the first ".tmp" that digits and "_" follow.
  const std::string name = path.filename().string();
  if (name.size() < 2 || name[0] != '.') return false;
  std::size_t tmp = name.find(".tmp", 1), end = std::string::npos;
  for (; tmp != std::string::npos; tmp = name.find(".tmp", tmp + 1)) {
    end = tmp + 4;
    while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
    if (end > tmp + 4 && end < name.size() && name[end] == '_') break;
  }
  if (tmp == std::string::npos) return false;
  const long pid = std::stol(name.substr(tmp + 4, end - tmp - 4));
  // A live writer (this process, or another command writing beside us) keeps its temporaries.
  return pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

std::size_t RemoveStaleTemporaries(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return 0;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if ((entry.is_regular_file() || entry.is_directory()) && IsStaleTemporary(entry.path())) stale.push_back(entry.path());
  }
  for (const auto& path : stale) std::filesystem::remove_all(path, error);
  return stale.size();
}

std::size_t RemoveStaleTemporariesOf(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(folder, error)) return 0;
  const std::string prefix = "." + file.stem().string() + ".tmp";
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (entry.is_regular_file() && entry.path().filename().string().rfind(prefix, 0) == 0 &&
        IsStaleTemporary(entry.path())) {
      stale.push_back(entry.path());
    }
  }
  for (const auto& path : stale) std::filesystem::remove(path, error);
  return stale.size();
}

}  // namespace lutex
