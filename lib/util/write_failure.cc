#include "lib/util/write_failure.h"

#include <sys/statvfs.h>

#include <cerrno>
#include <cstring>

#include "lib/util/memory_budget.h"

namespace lutex {

namespace {

// Free bytes for an unprivileged writer on the file system holding `path` (or its nearest existing
// ancestor); -1 when unknown.
double FreeBytesAt(std::filesystem::path path) {
  while (!path.empty() && !std::filesystem::exists(path)) {
    if (path == path.parent_path()) return -1.0;
    path = path.parent_path();
  }
  struct statvfs info {};
  if (path.empty() || ::statvfs(path.c_str(), &info) != 0) return -1.0;
  return static_cast<double>(info.f_bavail) * static_cast<double>(info.f_frsize);
}

}  // namespace

std::string DescribeWriteFailure(const std::filesystem::path& path, int error_number, const std::string& fallback) {
  const std::filesystem::path folder = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  const double free_bytes = FreeBytesAt(folder);
  const bool full = error_number == ENOSPC || error_number == EDQUOT || (free_bytes >= 0.0 && free_bytes < 1024.0 * 1024.0);
  if (full) {
    std::string text = path.string() + ": the disk is full";
    if (error_number == EDQUOT) text = path.string() + ": the disk quota is exceeded";
    if (free_bytes >= 0.0) {
      text += " (" + (free_bytes < 1024.0 * 1024.0 ? std::to_string(static_cast<long long>(free_bytes / 1024.0)) + " KiB"
                                                   : FormatBytes(free_bytes)) +
              " free on the file system of " + folder.string() + ")";
    }
    return text;
  }
  return path.string() + ": cannot be written (" + (error_number != 0 ? std::strerror(error_number) : fallback) + ")";
}

}  // namespace lutex
