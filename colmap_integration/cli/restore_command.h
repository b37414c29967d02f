#pragma once


#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/restore_workspace.h"

namespace lutex {

// `lutex restore`: parses the options and calls RestoreWorkspace (restore_workspace.h).
int RunRestoreCommand(int argc, char** argv);

// Registers how to restore: the options of `lutex restore` except --workspace, --mesh, --lut, --coverage,
// --output, --input-encoding and --num-threads (which `lutex run` sets from its own).
void AddRestoreStageOptions(OptionParser& parser, RestoreOptions* options);

}  // namespace lutex
