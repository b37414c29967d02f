#pragma once

// Outputs are never left half-written: write to a temporary name beside the destination, then Commit()
// renames it into place (atomic on POSIX within one file system). An uncommitted temporary is removed
// by the destructor, so an exception during writing leaves no partial file and the old file intact.
// The temporary may also be a folder the writer creates and fills (a tileset): it is removed whole, and
// Commit() replaces a folder at the destination.

#include <cstddef>
#include <filesystem>

namespace lutex {

class AtomicOutputFile {
 public:
  // Creates the parent folder of `destination` if needed.
  explicit AtomicOutputFile(std::filesystem::path destination);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // Where to write now.
  const std::filesystem::path& temporary_path() const { return temporary_path_; }
  const std::filesystem::path& destination() const { return destination_; }

  // Renames the temporary file to the destination; throws if it does not exist.
  void Commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path temporary_path_;
  bool committed_ = false;
};

// Whether `path` is the temporary of a writer that was killed before it could commit or clean up
// (".NAME.tmpPID_N.EXT", or that with a suffix a library adds, such as GDAL's ".ovr.tmp", whose process
// PID no longer exists). A live writer's temporary, of this process or of another command writing beside
// it, is not stale.
bool IsStaleTemporary(const std::filesystem::path& path);

// Removes the stale temporaries under `folder` (recursively); returns how many. A missing folder has none.
std::size_t RemoveStaleTemporaries(const std::filesystem::path& folder);
// Removes the stale temporaries of the one file `file` (beside it); returns how many.
std::size_t RemoveStaleTemporariesOf(const std::filesystem::path& file);

}  // namespace lutex
