#pragma once

// A dive loaded once: a COLMAP workspace, its sparse model, the mesh of its scene and the mesh's ray-casting
// scene (the Embree BVH). `lutex run` loads it once and hands it to every stage; a stage run on its own
// (lutex restore, lutex texture, ...) loads it itself. Reading a mesh of millions of faces and building its
// BVH take seconds each; a dive's stages share one copy.
//
// Not movable: the ray-casting scene refers to the mesh it was built from.

#include <filesystem>
#include <memory>
#include <mutex>

#include "colmap_integration/io/workspace.h"
#include "lib/geometry/mesh.h"
#include "lib/geometry/sparse_model.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

class LoadedDive {
 public:
  // Finds the workspace at `workspace_root` and reads its model and `mesh_path`. Throws
  // std::runtime_error naming the file that is missing or wrong.
  LoadedDive(const std::filesystem::path& workspace_root, const std::filesystem::path& mesh_path);
  LoadedDive(const LoadedDive&) = delete;
  LoadedDive& operator=(const LoadedDive&) = delete;

  const Workspace& workspace() const { return workspace_; }
  const SparseModel& model() const { return model_; }
  const std::filesystem::path& mesh_path() const { return mesh_path_; }
  // Throw std::logic_error once the mesh is released.
  const Mesh& mesh() const;
  // Built on first use (`lutex tiles` casts each tile's piece of the mesh instead, and needs none).
  // Thread-safe.
  const RaycastScene& scene() const;

  // Frees the mesh and its scene, for a stage that keeps what it needs of them elsewhere (`lutex tiles`
  // keeps the mesh on disk tile by tile), so that they do not take memory for the whole dive while it runs.
  void ReleaseMesh();
  bool has_mesh() const { return !mesh_released_; }

 private:
  Workspace workspace_;
  SparseModel model_;
  std::filesystem::path mesh_path_;
  Mesh mesh_;
  bool mesh_released_ = false;
  mutable std::once_flag scene_built_;
  mutable std::unique_ptr<RaycastScene> scene_;
};

}  // namespace lutex
