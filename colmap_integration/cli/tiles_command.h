#pragma once

// `lutex tiles`.

namespace lutex {

// Parses the options and calls TilesWorkspace (colmap_integration/stages/tiles_workspace.h).
int RunTilesCommand(int argc, char** argv);

}  // namespace lutex
