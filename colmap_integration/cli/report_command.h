#pragma once

namespace lutex {

// `lutex report`: parses the options and calls WriteReport (report_workspace.h).
int RunReportCommand(int argc, char** argv);

}  // namespace lutex
