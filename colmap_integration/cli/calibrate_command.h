#pragma once


#include "colmap_integration/stages/calibrate_workspace.h"
#include "colmap_integration/cli/option_parser.h"

namespace lutex {

// `lutex calibrate --workspace W --mesh M --targets T [...]`: parses options, runs CalibrateWorkspace.
int RunCalibrateCommand(int argc, char** argv);

// Registers what to calibrate from and how: every option of `lutex calibrate` except --workspace, --mesh,
// --output, --input-encoding and --num-threads (which `lutex run` shares among its stages).
void AddCalibrateStageOptions(OptionParser& parser, CalibrateOptions* options);

}  // namespace lutex
