#include "tests/support/tree_snapshot.h"

#include <fstream>
#include <sstream>

namespace lutex::testing {

std::map<std::filesystem::path, std::string> TreeSnapshot(const std::filesystem::path& root) {
  std::map<std::filesystem::path, std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.is_symlink() || !entry.is_regular_file()) continue;
    std::ostringstream bytes;
    bytes << std::ifstream(entry.path(), std::ios::binary).rdbuf();
    files[std::filesystem::relative(entry.path(), root)] = bytes.str();
  }
  return files;
}

}  // namespace lutex::testing
