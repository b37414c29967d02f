#include "tests/support/gltf_validator.h"

#include "tests/support/run_command.h"

namespace lutex::testing {

GltfValidation ValidateGltf(const std::filesystem::path& model) {
  GltfValidation validation;
  const std::filesystem::path script = std::filesystem::path(LUTEX_SOURCE_DIR) / "scripts" / "gltf_validator";
  if (!HaveProgram("node")) {
    validation.output = "node is not installed (scripts/install_dependencies.sh installs it)";
    return validation;
  }
  if (!std::filesystem::exists(script / "node_modules" / "gltf-validator" / "package.json")) {
    validation.output = "the glTF validator is not installed in " + script.string() +
                        " (scripts/install_dependencies.sh installs it)";
    return validation;
  }
  const CommandResult result = RunCommand("node '" + (script / "validate.mjs").string() + "' '" + model.string() + "'");
  validation.ran = result.exit_code == 0 || result.exit_code == 1;
  validation.valid = result.exit_code == 0;
  validation.output = result.output;
  return validation;
}

}  // namespace lutex::testing
