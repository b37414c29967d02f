#pragma once

namespace lutex {

// `lutex run`: parses the options (command line and --config file) and calls RunWorkspace.
int RunRunCommand(int argc, char** argv);

}  // namespace lutex
