#pragma once

// Runs a shell command for peer tests (the colmap binary, the lutex CLI) and captures what it printed.

#include <string>

namespace lutex::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

CommandResult RunCommand(const std::string& command);

// True when `program` is on PATH.
bool HaveProgram(const std::string& program);

}  // namespace lutex::testing
