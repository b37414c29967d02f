#include "colmap_integration/stages/loaded_dive.h"

#include <stdexcept>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"

namespace lutex {

LoadedDive::LoadedDive(const std::filesystem::path& workspace_root, const std::filesystem::path& mesh_path)
    : workspace_(FindWorkspace(workspace_root)),
      model_(ReadSparseModel(workspace_.sparse_dir)),
      mesh_path_(mesh_path),
      mesh_(ReadMesh(mesh_path)) {}

const Mesh& LoadedDive::mesh() const {
  if (mesh_released_) throw std::logic_error("the dive's mesh was released");
  return mesh_;
}

const RaycastScene& LoadedDive::scene() const {
  if (mesh_released_) throw std::logic_error("the dive's mesh was released");
  std::call_once(scene_built_, [this] { scene_ = std::make_unique<RaycastScene>(mesh_); });
  return *scene_;
}

void LoadedDive::ReleaseMesh() {
  mesh_ = Mesh();
  scene_.reset();
  mesh_released_ = true;
}

}  // namespace lutex
