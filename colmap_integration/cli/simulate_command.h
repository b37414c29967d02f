#pragma once

namespace lutex {

// `lutex simulate --scene S --output W`: parses options, runs SimulateWorkspace, prints what went where.
int RunSimulateCommand(int argc, char** argv);

}  // namespace lutex
