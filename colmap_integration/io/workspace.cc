#include "colmap_integration/io/workspace.h"

#include <algorithm>
#include <stdexcept>

namespace lutex {

namespace fs = std::filesystem;

namespace {

bool HasSparseModel(const fs::path& folder) {
  return fs::exists(folder / "cameras.bin") || fs::exists(folder / "cameras.txt");
}

}  // namespace

fs::path CoverageLutPath(const fs::path& lut) { return lut.parent_path() / "coverage.lut"; }

fs::path CalibrationSummaryPath(const fs::path& lut) { return lut.parent_path() / "calibration_summary.json"; }

fs::path WaterPriorPath(const fs::path& lut) { return lut.parent_path() / "water_prior.json"; }

fs::path ExposureRecordPath(const fs::path& lut) { return lut.parent_path() / "exposure.json"; }

fs::path ConfidenceDirOf(const fs::path& restored) {
  fs::path confidence = restored;
  confidence += "_confidence";
  return confidence;
}

fs::path DenseWorkspace::DepthMapPath(const std::string& image_name, const std::string& type) const {
  return depth_maps_dir / (image_name + "." + type + ".bin");
}

fs::path DenseWorkspace::NormalMapPath(const std::string& image_name, const std::string& type) const {
  return normal_maps_dir / (image_name + "." + type + ".bin");
}

DenseWorkspace FindDenseWorkspace(const fs::path& root) {
  DenseWorkspace dense;
  dense.root = root;
  dense.images_dir = root / "images";
  dense.sparse_dir = root / "sparse";
  dense.depth_maps_dir = root / "stereo" / "depth_maps";
  dense.normal_maps_dir = root / "stereo" / "normal_maps";
  if (!fs::is_directory(dense.images_dir) || !HasSparseModel(dense.sparse_dir)) {
    throw std::runtime_error(root.string() + ": not a COLMAP dense workspace (needs images/ and a model in sparse/)");
  }
  if (fs::exists(root / "fused.ply")) dense.fused_ply = root / "fused.ply";
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("meshed-", 0) == 0 && entry.path().extension() == ".ply") dense.meshes.push_back(entry.path());
  }
  std::sort(dense.meshes.begin(), dense.meshes.end());
  return dense;
}

Workspace FindWorkspace(const fs::path& root) {
  if (!fs::is_directory(root)) throw std::runtime_error(root.string() + ": the workspace is not a folder");
  Workspace workspace;
  workspace.root = root;
  workspace.images_dir = root / "images";
  if (HasSparseModel(root / "sparse" / "0")) {
    workspace.sparse_dir = root / "sparse" / "0";
  } else if (HasSparseModel(root / "sparse")) {
    workspace.sparse_dir = root / "sparse";
  } else {
    throw std::runtime_error(root.string() +
                             ": no COLMAP sparse model (looked for cameras.bin or cameras.txt in sparse/0 and sparse)");
  }
  for (int index = 0; fs::is_directory(root / "dense" / std::to_string(index)); ++index) {
    workspace.dense.push_back(FindDenseWorkspace(root / "dense" / std::to_string(index)));
  }
  return workspace;
}

}  // namespace lutex
