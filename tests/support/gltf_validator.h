#pragma once

// The Khronos glTF-Validator, as scripts/install_dependencies.sh installs it (npm, under
// scripts/gltf_validator), run on a file.

#include <filesystem>
#include <string>

namespace lutex::testing {

struct GltfValidation {
  bool ran = false;    // false when node or the validator is not installed (`output` says which)
  bool valid = false;  // no errors and no warnings
  std::string output;  // the issues and the last line "errors=N warnings=N infos=N hints=N"
};

GltfValidation ValidateGltf(const std::filesystem::path& model);

}  // namespace lutex::testing
