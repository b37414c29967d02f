// The lutex command-line tool: one binary, COLMAP-style sub-commands. Only this function catches
// exceptions: it prints one line on stderr and returns non-zero. No standard library's own wording reaches
// the user: running out of memory and a file system's refusal are put in lutex's words.

#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <iostream>
#include <string>

#include "colmap_integration/cli/calibrate_command.h"
#include "colmap_integration/cli/mesh_command.h"
#include "colmap_integration/cli/mosaic_command.h"
#include "colmap_integration/cli/raycast_command.h"
#include "colmap_integration/cli/report_command.h"
#include "colmap_integration/cli/restore_command.h"
#include "colmap_integration/cli/run_command.h"
#include "colmap_integration/cli/simulate_command.h"
#include "colmap_integration/cli/texture_command.h"
#include "colmap_integration/cli/tiles_command.h"

namespace {

struct Command {
  const char* name;
  int (*run)(int, char**);
  const char* summary;
};

const Command kCommands[] = {
    {"calibrate", &lutex::RunCalibrateCommand, "fit the LUT from known-colour targets and/or correspondences (+ pure water)"},
    {"mesh", &lutex::RunMeshCommand, "a mesh of the scene from the sparse model (2.5-D height field), without a GPU"},
    {"mosaic", &lutex::RunMosaicCommand, "a georeferenced orthomosaic and DEM of the seafloor as Cloud-Optimized GeoTIFFs"},
    {"raycast", &lutex::RunRaycastCommand, "per-image depth and normal maps of a mesh (COLMAP .bin + previews)"},
    {"report", &lutex::RunReportCommand, "an HTML page about a workspace's LUT, residuals, restored images, texture"},
    {"restore", &lutex::RunRestoreCommand, "restore images to albedo with a calibrated LUT, with confidence maps"},
    {"run", &lutex::RunRunCommand, "all of it, resumable: calibrate, restore, texture and report in W/lutex/"},
    {"simulate", &lutex::RunSimulateCommand, "render a scene description into a COLMAP workspace with ground truth"},
    {"texture", &lutex::RunTextureCommand, "bake one albedo texture onto the mesh and write GLB (or glTF, OBJ, PLY)"},
    {"tiles", &lutex::RunTilesCommand, "the textured mesh as 3D Tiles 1.1 for web map viewers (CesiumJS), tile by tile"},
};

void PrintUsage(std::ostream& out) {
  out << "lutex: true colour for images taken under co-moving artificial light (seafloor robots, flash rigs).\n"
         "It reads a COLMAP workspace and a mesh, ray-casts the mesh into every image and works from there.\n\n"
         "Usage: lutex COMMAND [options]    (lutex COMMAND --help for a command's options)\n\nCommands:\n";
  for (const Command& command : kCommands) out << "  " << command.name << "  " << command.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
      std::strcmp(argv[1], "help") == 0) {
    PrintUsage(std::cout);
    return argc < 2 ? 1 : 0;
  }
  for (const Command& command : kCommands) {
    if (command.name != std::string(argv[1])) continue;
    const std::string prefix = std::string("lutex ") + command.name + ": error: ";
    try {
      return command.run(argc, argv);
    } catch (const std::bad_alloc&) {
      std::cerr << prefix << "ran out of memory; use fewer --num-threads, a lower --memory-limit, or a machine "
                             "with more memory\n";
    } catch (const std::filesystem::filesystem_error& error) {
      std::cerr << prefix << (error.path1().empty() ? std::string() : error.path1().string() + ": ")
                << error.code().message() << "\n";
    } catch (const std::exception& error) {
      std::cerr << prefix << error.what() << "\n";
    }
    return 1;
  }
  std::cerr << "lutex: unknown command '" << argv[1] << "' (lutex --help lists the commands)\n";
  return 1;
}
