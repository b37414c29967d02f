#pragma once

// Every regular file under a folder with its bytes, to assert that a command added, removed or changed
// nothing there ("inputs are sacred", "a failed command writes nothing"). Symbolic links are not followed.

#include <filesystem>
#include <map>
#include <string>

namespace lutex::testing {

// Relative path (to `root`) -> bytes.
std::map<std::filesystem::path, std::string> TreeSnapshot(const std::filesystem::path& root);

}  // namespace lutex::testing
