#include "lib/util/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <map>
#include <mutex>
#include <stdexcept>

#include "lib/util/logging.h"

namespace lutex {

namespace {

std::string Contents(int fd) {
  std::string text;
  char buffer[256];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t got; (got = ::read(fd, buffer, sizeof(buffer))) > 0;) text.append(buffer, static_cast<std::size_t>(got));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

std::string HolderText() {
  char host[256] = "unknown host";
  ::gethostname(host, sizeof(host) - 1);
  char started[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(started, sizeof(started), "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  return "pid " + std::to_string(::getpid()) + " on " + host + " (started " + started + ")\n";
}

// The locks this process holds, by absolute path, with how many holders share each. A child made by fork()
// inherits the map but not the holds: an entry counts only for the process that made it.
struct Hold {
  pid_t holder = 0;
  int count = 0;
};
std::mutex held_mutex;
std::map<std::filesystem::path, Hold>& HeldLocks() {
  static std::map<std::filesystem::path, Hold> held;
  return held;
}

}  // namespace

ExclusiveFileLock::ExclusiveFileLock(const std::filesystem::path& path, const std::string& what)
    : path_(std::filesystem::absolute(path).lexically_normal()) {
  {
    const std::lock_guard<std::mutex> guard(held_mutex);
    const auto held = HeldLocks().find(path_);
    if (held != HeldLocks().end() && held->second.holder == ::getpid()) {  // lutex run, then one of its stages
      ++held->second.count;
      nested_ = true;
      return;
    }
  }
  Acquire(what);
  const std::lock_guard<std::mutex> guard(held_mutex);
  HeldLocks()[path_] = Hold{::getpid(), 1};
}

void ExclusiveFileLock::Acquire(const std::string& what) {
  const std::filesystem::path& path = path_;
  created_folder_ = std::filesystem::create_directories(path.parent_path());
  // A holder removes the file as it releases the lock; a file opened just before that is no longer the
  // lock file once we hold it, so try again on the file now at `path`.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw std::runtime_error(path.string() + ": cannot create the lock file: " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const std::string holder = Contents(fd);
      ::close(fd);
      throw std::runtime_error(what + " is in use by lutex " + (holder.empty() ? "(another process)" : holder) +
                               "; wait for it to finish (lock: " + path.string() + ")");
    }
    struct stat opened {}, current {};
    if (::fstat(fd, &opened) != 0 || ::stat(path.c_str(), &current) != 0 || opened.st_ino != current.st_ino ||
        opened.st_dev != current.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string stale = Contents(fd);
    if (!stale.empty()) {
      LogWarning() << what << " was locked by lutex " << stale
                   << ", which ended without releasing it (killed or crashed); taking it over";
    }
    const std::string holder = HolderText();
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, holder.data(), holder.size(), 0) != static_cast<ssize_t>(holder.size())) {
      ::close(fd);
      throw std::runtime_error(path.string() + ": cannot write the lock file: " + std::strerror(errno));
    }
    fd_ = fd;
    return;
  }
  throw std::runtime_error(path.string() + ": the lock file keeps being replaced; is another lutex starting?");
}

ExclusiveFileLock::~ExclusiveFileLock() {
  {
    const std::lock_guard<std::mutex> guard(held_mutex);
    const auto held = HeldLocks().find(path_);
    if (held != HeldLocks().end() && held->second.holder == ::getpid() && --held->second.count == 0) {
      HeldLocks().erase(held);
    }
  }
  if (nested_ || fd_ < 0) return;
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);  // while still holding the lock, so nobody locks a removed file
  ::close(fd_);
  // A command that failed before writing anything leaves no folder behind either (remove keeps a folder
  // that is not empty).
  if (created_folder_) std::filesystem::remove(path_.parent_path(), ignored);
}

}  // namespace lutex
