#pragma once

namespace lutex {

// `lutex calibrate --workspace W --mesh M --targets T [...]`: parses options, runs CalibrateWorkspace.
int RunCalibrateCommand(int argc, char** argv);

}  // namespace lutex
