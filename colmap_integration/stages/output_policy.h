#pragma once

// Inputs are sacred: no command writes over or inside what it reads. Every stage lists the paths it reads
// (the workspace's images and model, the mesh, targets, LUTs, other workspaces) and the paths it writes
// (files or folders), and refuses, before it reads anything, an output that
//   - is an input                       (`lutex texture --output W/scene/mesh.ply` on that mesh),
//   - lies inside an input folder       (`lutex restore --output W/images`, `--output W/sparse/0/x`),
//   - contains an input                 (`lutex restore --output W`, which holds W/images).
// Paths are compared after resolving `.`, `..` and symbolic links of the parts that exist, so another
// spelling of the same place is caught too.

#include <filesystem>
#include <string>
#include <vector>

#include "colmap_integration/io/workspace.h"

namespace lutex {

class InputsAndOutputs {
 public:
  // `what` names the input in the error ("the mesh", "the images of W"). Empty paths are ignored.
  void AddInput(const std::filesystem::path& path, const std::string& what);
  // The workspace's image folder and sparse model folder.
  void AddWorkspace(const Workspace& workspace, const std::string& what);
  void AddOutput(const std::filesystem::path& path);

  // Throws std::runtime_error naming the output and the input, e.g. "W/images/x: the output lies inside
  // the images of the workspace (W/images); choose an output outside the inputs", or naming the output
  // and the file in its way ("afile/x: cannot be written, afile is a file, not a folder").
  void Check() const;
  // Removes what killed writers left of the outputs (lib/util/atomic_output.h: in an output folder, every
  // stale temporary under it; beside an output file, that file's), saying so; a live writer's are kept.
  void RemoveStaleTemporaries() const;
  // Whether an output is `folder` or lies inside it (paths resolved as for Check).
  bool WritesInside(const std::filesystem::path& folder) const;

 private:
  struct Input {
    std::filesystem::path path;
    std::string what;
  };
  std::vector<Input> inputs_;
  std::vector<std::filesystem::path> outputs_;
};

}  // namespace lutex
