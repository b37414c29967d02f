#pragma once

// Command-line options of one sub-command: `--name value` or `--name=value`, flags without a value,
// `--help` that prints every option with its default and description. Unknown options, missing values
// and unparsable numbers are errors that name the option.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lutex {

class OptionParser {
 public:
  // `usage` is the first line of --help ("lutex raycast --workspace W --mesh M [options]"), `summary`
  // a paragraph that explains what the command does.
  OptionParser(std::string usage, std::string summary);

  void AddPath(const std::string& name, std::filesystem::path* value, const std::string& help, bool required = false);
  void AddInt(const std::string& name, int* value, const std::string& help);
  void AddDouble(const std::string& name, double* value, const std::string& help);
  void AddString(const std::string& name, std::string* value, const std::string& help);
  // A flag sets *value = true; `--no-NAME` sets it to false.
  void AddFlag(const std::string& name, bool* value, const std::string& help);

  // Parses argv[first..argc). Returns false when --help was asked for (help has been printed on stdout).
  // Throws std::invalid_argument on any error.
  bool Parse(int argc, char** argv, int first);

  std::string Help() const;

 private:
  struct Option {
    std::string name;
    std::string help;
    std::string default_text;
    bool required = false;
    bool is_flag = false;
    bool seen = false;
    std::function<void(const std::string&)> set;
  };
  Option& Find(const std::string& name);

  std::string usage_;
  std::string summary_;
  std::vector<Option> options_;
};

}  // namespace lutex
