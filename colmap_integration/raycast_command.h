#pragma once

namespace lutex {

// `lutex raycast ...`: parses options, runs RaycastWorkspace, prints where the outputs went.
// Returns the process exit code; throws on errors (main prints them).
int RunRaycastCommand(int argc, char** argv);

}  // namespace lutex
