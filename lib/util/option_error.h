#pragma once

// Errors in options, worded with the options' field names so the library never speaks of flags. A
// message marks each field in braces, "{targets_workspace} needs {targets}"; what() reads "targets_workspace
// needs targets", and a command line shows it with its own names for the fields (the CLI's option parser
// turns "{targets_workspace}" into "--targets-workspace").

#include <functional>
#include <stdexcept>
#include <string>

namespace lutex {

class OptionError : public std::invalid_argument {
 public:
  explicit OptionError(const std::string& message);

  // The message with each "{field}" replaced by name_of(field).
  std::string Render(const std::function<std::string(const std::string& field)>& name_of) const;

 private:
  std::string message_;
};

}  // namespace lutex
