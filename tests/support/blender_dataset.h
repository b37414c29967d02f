#pragma once

// The shared Blender Cycles datasets (../shared/datasets/dev/*, see their README): the model, mesh,
// light rig and water of one dataset, read from its metadata.json, as lutex's simulator takes them. The
// model is read with the COLMAP reader (colmap_integration/io): tests using this link lutex_colmap_io.

#include <filesystem>
#include <string>

#include "lib/geometry/sparse_model.h"
#include "lib/geometry/mesh.h"
#include "lib/model/light_rig.h"
#include "lib/model/water.h"
#include "tests/support/shared_datasets.h"

namespace lutex::testing {

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
