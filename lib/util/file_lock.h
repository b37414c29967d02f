#pragma once

// An exclusive lock on a file, for one writer per workspace (`lutex run` takes W/lutex/.lock). Taken with
// flock(2): the kernel releases it when the holder ends, however it ends (crash, SIGKILL), so a lock is
// never stuck. The file holds the holder's pid, host and start time, for the message a second writer
// gets; a file left by a killed holder (present but not locked) is taken over with a warning. The file is
// removed when the lock is released, and so is its folder if the lock created it and it is still empty.
// A process that holds a lock may take it again (`lutex run` holds the workspace's, then each of its stages
// takes it): the inner holds share the outer one, which alone releases it.

#include <filesystem>
#include <string>

namespace lutex {

class ExclusiveFileLock {
 public:
  // Creates `path`'s folder if needed. Throws std::runtime_error "`what` is in use by lutex pid N on HOST
  // (started T)" when another process holds the lock; shares it when this process does.
  ExclusiveFileLock(const std::filesystem::path& path, const std::string& what);
  ~ExclusiveFileLock();
  ExclusiveFileLock(const ExclusiveFileLock&) = delete;
  ExclusiveFileLock& operator=(const ExclusiveFileLock&) = delete;

 private:
  void Acquire(const std::string& what);

  std::filesystem::path path_;  // absolute
  bool nested_ = false;          // shares a hold this process had already
  bool created_folder_ = false;  // the lock's folder did not exist before
  int fd_ = -1;
};

}  // namespace lutex
