#pragma once

// A fresh folder under the system temp dir, removed with everything in it at the end of the test.

#include <filesystem>

namespace lutex::testing {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace lutex::testing
