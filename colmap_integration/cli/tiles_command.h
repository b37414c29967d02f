#pragma once

// `lutex tiles`, and the tiling options `lutex run` shares.

#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/tiles_workspace.h"

namespace lutex {

// Parses the options and calls TilesWorkspace (colmap_integration/stages/tiles_workspace.h).
int RunTilesCommand(int argc, char** argv);

// Registers --tile-faces (options->tree.max_faces): a whole number of faces, at least 1.
void AddTileFacesOption(OptionParser& parser, TilesOptions* options);

}  // namespace lutex
