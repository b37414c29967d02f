#pragma once

namespace lutex {

// `lutex restore --workspace W --mesh M --lut L [--output DIR]`: parses options, runs RestoreWorkspace.
int RunRestoreCommand(int argc, char** argv);

}  // namespace lutex
