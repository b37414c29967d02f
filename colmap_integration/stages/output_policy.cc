#include "colmap_integration/stages/output_policy.h"

#include <stdexcept>

namespace lutex {

namespace fs = std::filesystem;

namespace {

fs::path Resolved(const fs::path& path) {
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path), error);
  return error ? fs::absolute(path).lexically_normal() : resolved;
}

// Whether `inner` is `outer` or lies below it, component by component.
bool IsWithin(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

void InputsAndOutputs::AddInput(const fs::path& path, const std::string& what) {
  if (!path.empty()) inputs_.push_back({path, what});
}

void InputsAndOutputs::AddWorkspace(const Workspace& workspace, const std::string& what) {
  AddInput(workspace.images_dir, "the images of " + what);
  AddInput(workspace.sparse_dir, "the sparse model of " + what);
}

void InputsAndOutputs::AddOutput(const fs::path& path) {
  if (!path.empty()) outputs_.push_back(path);
}

void InputsAndOutputs::Check() const {
  std::vector<fs::path> resolved_inputs;
  for (const Input& input : inputs_) resolved_inputs.push_back(Resolved(input.path));
  for (const fs::path& output : outputs_) {
    const fs::path resolved_output = Resolved(output);
    for (std::size_t i = 0; i < inputs_.size(); ++i) {
      const Input& input = inputs_[i];
      const fs::path& resolved_input = resolved_inputs[i];
      const bool inside = IsWithin(resolved_output, resolved_input);
      const bool contains = IsWithin(resolved_input, resolved_output);
      if (!inside && !contains) continue;
      const std::string relation = inside && contains ? "is " : inside ? "lies inside " : "contains ";
      throw std::runtime_error(output.string() + ": the output " + relation + input.what + " (" + input.path.string() +
                               "); lutex never writes over or inside its inputs: choose an output outside them");
    }
  }
}

}  // namespace lutex
