#pragma once

// Where things are in a COLMAP workspace:
//   W/images/                    the input images (names in the model are relative to it)
//   W/sparse/0/ or W/sparse/     the sparse model (binary or text)
//   W/dense/N/                   image_undistorter output: images/, sparse/, stereo/depth_maps,
//                                stereo/normal_maps, and after fusion/meshing fused.ply, meshed-*.ply
//   W/georef.json                where the model sits on the Earth (lib/geo/georeference.h); optional
//   W/lutex/                     everything lutex writes, unless told otherwise

#include <filesystem>
#include <string>
#include <vector>

namespace lutex {

struct DenseWorkspace {
  std::filesystem::path root;  // W/dense/N (or a folder with the same layout)
  std::filesystem::path images_dir;
  std::filesystem::path sparse_dir;
  std::filesystem::path depth_maps_dir;
  std::filesystem::path normal_maps_dir;
  std::filesystem::path fused_ply;              // empty when absent
  std::vector<std::filesystem::path> meshes;    // meshed-*.ply present, sorted

  // stereo/depth_maps/NAME.TYPE.bin with TYPE "geometric" or "photometric".
  std::filesystem::path DepthMapPath(const std::string& image_name, const std::string& type) const;
  std::filesystem::path NormalMapPath(const std::string& image_name, const std::string& type) const;
};

struct Workspace {
  std::filesystem::path root;
  std::filesystem::path images_dir;
  std::filesystem::path sparse_dir;
  std::vector<DenseWorkspace> dense;  // dense/0, dense/1, ... present, in order

  std::filesystem::path OutputDir() const { return root / "lutex"; }
  std::filesystem::path GeoreferencePath() const { return root / "georef.json"; }
  // The default outputs under OutputDir(), stated once for the commands that write them and those that
  // read them (run, report).
  std::filesystem::path RaycastDir() const { return OutputDir() / "raycast"; }
  std::filesystem::path MeshPath() const { return OutputDir() / "mesh" / "mesh.ply"; }
  std::filesystem::path LutPath() const { return OutputDir() / "calibration" / "lut.lut"; }
  std::filesystem::path RestoredDir() const { return OutputDir() / "restored"; }
  std::filesystem::path ModelPath() const { return OutputDir() / "model.glb"; }
  std::filesystem::path TilesDir() const { return OutputDir() / "tiles"; }
  std::filesystem::path OrthomosaicPath() const { return OutputDir() / "mosaic" / "ortho.tif"; }
  std::filesystem::path DemPath() const { return OutputDir() / "mosaic" / "dem.tif"; }
  std::filesystem::path RunRecordsDir() const { return OutputDir() / "run"; }
  std::filesystem::path ReportDir() const { return OutputDir() / "report"; }
};

// Files lutex calibrate writes beside the LUT `lut`: the per-node data coverage and the summary.
std::filesystem::path CoverageLutPath(const std::filesystem::path& lut);
std::filesystem::path CalibrationSummaryPath(const std::filesystem::path& lut);
// The fitted water and rig (lib/calibration/water_prior.h), a rig file --shading-rig reads.
std::filesystem::path WaterPriorPath(const std::filesystem::path& lut);
// The exposure the LUT is for and the fitted per-image gains (lib/calibration/exposure_record.h).
std::filesystem::path ExposureRecordPath(const std::filesystem::path& lut);

// The confidence maps of the restored images in `restored`: the sibling folder RESTORED_confidence (not a
// subfolder, so tools collecting restored images by name do not pick them up).
std::filesystem::path ConfidenceDirOf(const std::filesystem::path& restored);

// Throws std::runtime_error naming `root` when it is not a folder or has no sparse model.
Workspace FindWorkspace(const std::filesystem::path& root);

// Throws std::runtime_error naming `root` when it lacks images/ or sparse/.
DenseWorkspace FindDenseWorkspace(const std::filesystem::path& root);

}  // namespace lutex
