#pragma once

// The shared Blender Cycles datasets (../shared/datasets/dev/*, see their README): the model, mesh,
// light rig and water of one dataset, read from its metadata.json, as lutex's simulator takes them.

#include <filesystem>
#include <optional>
#include <string>

#include "colmap_integration/sparse_model.h"
#include "lib/geometry/mesh.h"
#include "lib/model/light_rig.h"
#include "lib/model/water.h"

namespace lutex::testing {

// The dev/ folder of the shared datasets, or nothing when it is absent (tests then skip).
std::optional<std::filesystem::path> SharedDevDatasets();

struct BlenderDataset {
  std::filesystem::path root;
  std::string kind;  // "calib_boards", "checker", "seafloor", "purewater", "inair_whiteboard"...
  SparseModel model;
  Mesh mesh;         // empty for pure water
  LightRig rig;
  Water water;
};

BlenderDataset LoadBlenderDataset(const std::filesystem::path& root);

}  // namespace lutex::testing
