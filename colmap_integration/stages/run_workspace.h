#pragma once

// `lutex run`: the whole pipeline on one COLMAP workspace, everything under W/lutex/:
//
//   mesh        (only without a mesh)    mesh/          mesh.ply (lutex mesh: from a fused cloud or the
//                                                       sparse points), unless a dense workspace has its
//                                                       own (W/dense/N/meshed-*.ply)
//   raycast     (only with raycast_maps) raycast/       depth and normal maps in COLMAP's format
//   calibrate   (unless a LUT is given)  calibration/   lut.lut, coverage.lut, calibration_summary.json, slabs/
//   restore                              restored/, restored_confidence/
//   texture                              model.glb
//   mosaic      (unless mosaic is off)   mosaic/        ortho.tif, dem.tif (lutex mosaic); skipped with a
//                                                       note for a model with no georeference that is not z-up
//   tiles       (unless tiles is off)    tiles/         tileset.json and its GLB tiles (lutex tiles); skipped
//                                                       with a note for a model with no georeference
//   report                               report/index.html (lutex report)
//
// Resumable: each stage keeps a record in W/lutex/run/STAGE.json (stage_record.h) of what it consumed
// (the files it reads, by size and modification time or, for the LUT, by content; the settings that shape
// its output). A stage whose record says done with the same fingerprint is skipped; a stage that was cut
// off (killed, crashed) runs again, and restore and raycast skip the images they had finished. Every file
// is written under a temporary name and renamed when complete (leftover temporaries of a killed run are
// removed), so a run killed at any point and started again ends with the same outputs as one that was
// never interrupted.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "colmap_integration/stages/calibrate_workspace.h"
#include "colmap_integration/stages/mesh_workspace.h"
#include "colmap_integration/stages/mosaic_workspace.h"
#include "colmap_integration/stages/raycast_workspace.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "colmap_integration/stages/tiles_workspace.h"

namespace lutex {

struct RunOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;  // empty: the mesh stage finds or makes one
  MeshOptions mesh_options;     // how, without a dense workspace's mesh
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // A LUT calibrated before (e.g. from the rig's calibration dive) instead of the calibrate stage; its
  // coverage.lut beside it is used when present.
  std::filesystem::path lut;
  // Also write per-image depth and normal maps (raycast stage). Off by default: the other stages ray-cast
  // on the fly, and the maps of a dive are large (16 bytes per pixel: 190 MB per 12 MP image).
  bool raycast_maps = false;
  // Stage options; the workspace, mesh, encodings, inputs and outputs of each are set by the run.
  RaycastOptions raycast;
  CalibrateOptions calibrate;
  RestoreOptions restore;
  TextureOptions texture;
  MosaicOptions mosaic;  // its view selection and fusion are the texture's
  bool make_mosaic = true;
  TilesOptions tiles;  // its baking options and up axis are the texture's
  bool make_tiles = true;
  // Per stage ("raycast", "calibrate", "restore", "texture", "mosaic", "tiles"), the settings that shape its output, by
  // option name, as the command line and config file gave them; part of the stage's fingerprint.
  std::map<std::string, std::map<std::string, std::string>> stage_settings;
  // Redo every stage even when its record says it is up to date.
  bool force = false;
  // Write the HTML report at the end.
  bool report = true;
  int num_threads = 0;
  // Every stage's memory limit (stage_memory.h); 0: the machine's available memory.
  std::size_t memory_limit_bytes = 0;

  void Check() const;
};

struct RunStageSummary {
  std::string stage;
  std::string status;  // "done", "resumed", "up to date" or "not needed"
  double seconds = 0.0;  // of the run that produced the outputs (also when up to date)
  std::string summary;   // the stage command's summary lines
};

struct RunSummary {
  std::vector<RunStageSummary> stages;
  std::filesystem::path mesh;  // the one the mesh stage found or made; empty when given
  std::filesystem::path lut;
  std::filesystem::path restored;
  std::filesystem::path confidence;
  std::filesystem::path model;
  std::filesystem::path mosaic;  // the orthomosaic; empty when not made
  std::filesystem::path tileset;  // the 3D Tiles' tileset.json; empty when not made
  std::filesystem::path report;  // empty without report
  double seconds = 0.0;
};

RunSummary RunWorkspace(const RunOptions& options);

}  // namespace lutex
