#include "lib/util/atomic_output.h"

#include <unistd.h>

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
    std::filesystem::remove(temporary_path_, ignored);
  }
}

void AtomicOutputFile::Commit() {
  if (!std::filesystem::exists(temporary_path_)) {
    throw std::runtime_error(destination_.string() + ": nothing was written");
  }
  std::filesystem::rename(temporary_path_, destination_);
  committed_ = true;
}

std::size_t RemoveStaleTemporaries(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return 0;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos) {
      stale.push_back(entry.path());
    }
  }
  for (const auto& path : stale) std::filesystem::remove(path, error);
  return stale.size();
}

}  // namespace lutex
