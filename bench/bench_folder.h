#pragma once

// The scratch folder of a benchmark, /tmp/NAME, held for as long as the benchmark runs and emptied when it
// is taken (what an earlier run kept with --keep goes). A second run of the same benchmark beside the
// first would delete the first's dives under it; instead it exits with one line naming the first
// (lib/util/file_lock.h, on /tmp/NAME.lock, which the kernel releases however the holder ends).

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "lib/util/file_lock.h"

namespace lutex::bench {

class BenchFolder {
 public:
  explicit BenchFolder(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / name) {
    try {
      lock_ = std::make_unique<ExclusiveFileLock>(path_.string() + ".lock", path_.string());
    } catch (const std::runtime_error& error) {
      std::fprintf(stderr, "%s\n", error.what());
      std::exit(2);
    }
    std::filesystem::remove_all(path_);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<ExclusiveFileLock> lock_;
};

}  // namespace lutex::bench
