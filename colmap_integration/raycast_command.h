#pragma once

#include <ostream>

#include "colmap_integration/option_parser.h"
#include "colmap_integration/raycast_workspace.h"

namespace lutex {

// `lutex raycast`: parses the options and calls RaycastWorkspace (raycast_workspace.h).
int RunRaycastCommand(int argc, char** argv);

// The lines `lutex raycast` prints when done.
void PrintRaycastSummary(std::ostream& out, const RaycastSummary& summary);

}  // namespace lutex
