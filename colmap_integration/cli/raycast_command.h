#pragma once


#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/raycast_workspace.h"

namespace lutex {

// `lutex raycast`: parses the options and calls RaycastWorkspace (raycast_workspace.h).
int RunRaycastCommand(int argc, char** argv);

}  // namespace lutex
