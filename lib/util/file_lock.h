#pragma once

// An exclusive lock on a file, for one writer per workspace (`lutex run` takes W/lutex/.lock). Taken with
// flock(2): the kernel releases it when the holder ends, however it ends (crash, SIGKILL), so a lock is
// never stuck. The file holds the holder's pid, host and start time, for the message a second writer
// gets; a file left by a killed holder (present but not locked) is taken over with a warning. The file is
// removed when the lock is released, and so is its folder if the lock created it and it is still empty.

#include <filesystem>
#include <string>

namespace lutex {

class ExclusiveFileLock {
 public:
  // Creates `path`'s folder if needed. Throws std::runtime_error "`what` is in use by lutex pid N on HOST
  // (started T)" when another process holds the lock.
  ExclusiveFileLock(const std::filesystem::path& path, const std::string& what);
  ~ExclusiveFileLock();
  ExclusiveFileLock(const ExclusiveFileLock&) = delete;
  ExclusiveFileLock& operator=(const ExclusiveFileLock&) = delete;

 private:
  std::filesystem::path path_;
  bool created_folder_ = false;  // the lock's folder did not exist before
  int fd_ = -1;
};

}  // namespace lutex
