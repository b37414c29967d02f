#include "colmap_integration/stages/output_policy.h"

#include <stdexcept>
#include <system_error>

#include "lib/util/atomic_output.h"
#include "lib/util/logging.h"

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

// An output can be made only if the nearest part of its path that exists is a folder (or, for the
// output itself, what it will replace): "afile/x" with afile a file cannot.
void CheckCanBeCreated(const fs::path& output) {
  std::error_code error;
  for (fs::path ancestor = output.parent_path(); !ancestor.empty(); ancestor = ancestor.parent_path()) {
    const fs::file_status status = fs::status(ancestor, error);
    if (status.type() == fs::file_type::not_found) {
      if (ancestor == ancestor.parent_path()) break;
      continue;
    }
    if (status.type() != fs::file_type::directory) {
      throw std::runtime_error(output.string() + ": cannot be written, " + ancestor.string() +
                               " is a file, not a folder");
    }
    return;
  }
}

}  // namespace

void InputsAndOutputs::AddInput(const fs::path& path, const std::string& what) {
  if (!path.empty()) inputs_.push_back({path, what});
}

void InputsAndOutputs::AddWorkspace(const Workspace& workspace, const std::string& what) {
  AddInput(workspace.images_dir, "the images of " + what);
  AddInput(workspace.sparse_dir, "the sparse model of " + what);
}

bool InputsAndOutputs::WritesInside(const fs::path& folder) const {
  const fs::path resolved_folder = Resolved(folder);
  for (const fs::path& output : outputs_) {
    if (IsWithin(Resolved(output), resolved_folder)) return true;
  }
  return false;
}

void InputsAndOutputs::AddOutput(const fs::path& path) {
  if (!path.empty()) outputs_.push_back(path);
}

void InputsAndOutputs::Check() const {
  for (const fs::path& output : outputs_) CheckCanBeCreated(output);
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

void InputsAndOutputs::RemoveStaleTemporaries() const {
  for (const fs::path& output : outputs_) {
    std::error_code error;
    const std::size_t removed = fs::is_directory(output, error) ? lutex::RemoveStaleTemporaries(output)
                                                                : RemoveStaleTemporariesOf(output);
    if (removed > 0) {
      LogInfo() << "removed " << removed << " unfinished file(s) of an interrupted command at " << output.string();
    }
  }
}

}  // namespace lutex
