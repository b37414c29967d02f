#include "colmap_integration/cli/run_command.h"

#include <iomanip>
#include <iostream>

#include "colmap_integration/cli/calibrate_command.h"
#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/mesh_command.h"
#include "colmap_integration/cli/mosaic_command.h"
#include "colmap_integration/cli/restore_command.h"
#include "colmap_integration/cli/texture_command.h"
#include "colmap_integration/cli/tiles_command.h"
#include "colmap_integration/stages/run_workspace.h"

namespace lutex {

int RunRunCommand(int argc, char** argv) {
  RunOptions options;
  OptionParser parser(
      "lutex run --workspace W [--mesh M] [--targets T [--targets-workspace W2 --targets-mesh M2]]\n"
      "          [--pure-water W3] [--correspondences [--grey-world V]] [--in-air] [--config FILE]",
      "Runs the whole pipeline on the COLMAP workspace W with the mesh M of its scene (in the model's world\n"
      "frame) and writes everything under W/lutex/:\n"
      "  mesh       only without --mesh: a dense workspace's W/dense/N/meshed-*.ply, else a 2.5-D surface\n"
      "             from the sparse model (options as lutex mesh)            -> mesh/mesh.ply\n"
      "  calibrate  the LUT of light and water from known-colour targets, correspondences between W's images\n"
      "             and/or pure-water images (options as lutex calibrate)   -> calibration/lut.lut\n"
      "  restore    every image restored to albedo, with confidence maps   -> restored/, restored_confidence/\n"
      "  texture    one albedo texture for the mesh                          -> model.glb\n"
      "  mosaic     a georeferenced orthomosaic and DEM (options as lutex mosaic; --no-mosaic to skip)\n"
      "                                                                      -> mosaic/ortho.tif, dem.tif\n"
      "  tiles      3D Tiles for web map viewers, for a georeferenced model (--tile-faces as\n"
      "             lutex tiles; --no-tiles to skip)                         -> tiles/tileset.json\n"
      "  report     an HTML page to judge the result                         -> report/index.html\n"
      "(and with --depth-maps a raycast stage -> raycast/). Stop it at any time, even with kill -9, and run it\n"
      "again: finished stages are skipped (W/lutex/run/STAGE.json records what each consumed: inputs by size\n"
      "and time, the LUT by content, the options that shape the output), an interrupted stage resumes\n"
      "(restore skips the images it had written), and the outputs are the same as those of an uninterrupted\n"
      "run. Change an input or an option and the stages that depend on it run again. Every option below can\n"
      "also come from --config FILE.");
  parser.SetGroup("run");
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("mesh", &options.mesh,
                 "Mesh of W's scene in the model's world frame (.ply, .obj, .off, .stl); without it, a dense\n"
                 "      workspace's W/dense/N/meshed-*.ply, else one made from the sparse model (lutex mesh).");
  AddImageEncodingOption(parser, "input-encoding", &options.input_encoding, "How W's images are encoded:");
  parser.AddPath("lut", &options.lut, "A LUT calibrated before: skips the calibrate stage.");
  parser.AddFlag("depth-maps", &options.raycast_maps,
                 "Also write per-image depth and normal maps (COLMAP format, W/lutex/raycast; 16 bytes a pixel).");
  parser.AddFlag("force", &options.force, "Run every stage, even those that are up to date.");
  parser.AddFlag("report", &options.report, "Write the HTML report at the end (--no-report to skip).");
  AddThreadsOption(parser, &options.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  // How much the tiles and mosaic stages keep decoded, not what they make: not a stage setting, so changing
  // it runs nothing again.
  AddImageCacheOption(parser, {&options.tiles.picture_cache_bytes, &options.mosaic.picture_cache_bytes});
  parser.SetGroup("mesh");
  AddMeshStageOptions(parser, &options.mesh_options);
  parser.SetGroup("calibrate");
  AddCalibrateStageOptions(parser, &options.calibrate);
  parser.SetGroup("restore");
  AddRestoreStageOptions(parser, &options.restore);
  parser.SetGroup("texture");
  AddTextureStageOptions(parser, &options.texture);
  parser.SetGroup("mosaic");
  parser.AddFlag("mosaic", &options.make_mosaic, "Make the orthomosaic and DEM (--no-mosaic to skip).");
  AddMosaicStageOptions(parser, &options.mosaic);
  parser.SetGroup("tiles");
  parser.AddFlag("tiles", &options.make_tiles,
                 "Make 3D Tiles when the model is georeferenced (--no-tiles to skip).");
  AddTileFacesOption(parser, &options.tiles);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    for (const char* stage : {"mesh", "calibrate", "restore", "texture", "mosaic", "tiles"}) {
      options.stage_settings[stage] = parser.Settings(stage);
    }

    const RunSummary summary = RunWorkspace(options);
    std::cout << "\nlutex run: done in " << std::fixed << std::setprecision(1) << summary.seconds << " s\n";
    for (const RunStageSummary& stage : summary.stages) {
      std::cout << "\n[" << stage.stage << ": " << stage.status;
      if (stage.status != "not needed") std::cout << ", " << stage.seconds << " s";
      std::cout << "]\n" << stage.summary;
    }
    std::cout << "\nOutputs:\n";
    if (!summary.mesh.empty()) std::cout << "  mesh:            " << summary.mesh.string() << "\n";
    std::cout
              << "  LUT:             " << summary.lut.string() << "\n"
              << "  restored images: " << summary.restored.string() << "\n"
              << "  confidence maps: " << summary.confidence.string() << "\n"
              << "  textured model:  " << summary.model.string() << "\n";
    if (!summary.mosaic.empty()) std::cout << "  orthomosaic:     " << summary.mosaic.string() << "\n";
    if (!summary.tileset.empty()) std::cout << "  3D Tiles:        " << summary.tileset.string() << "\n";
    if (!summary.report.empty()) std::cout << "  report:          " << summary.report.string() << "\n";
  });
  return 0;
}

}  // namespace lutex
