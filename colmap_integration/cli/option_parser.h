#pragma once

// Command-line options of one sub-command: `--name value` or `--name=value`, flags without a value,
// `--help` that prints every option with its default and description. Unknown options, missing values
// and unparsable numbers are errors that name the option.
//
// Every command also reads options from a file with `--config FILE`: one option per line, written as on
// the command line without the leading dashes,
//
//   # lutex run options for the 2026 dive
//   targets = calibration/targets.json     (relative paths are relative to the file's folder)
//   correspondences                        (a flag; `no-correspondences` turns it off)
//   lut-nx = 40
//
// Blank lines and lines starting with '#' are ignored. Options on the command line win over the file's.
// Every command also takes `--log-level debug|info|warning|error|silent`.

#include <filesystem>
#include <functional>
#include <map>
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
  // A whole number in [min, max]; other values are errors naming the option, the range and the value.
  void AddIntInRange(const std::string& name, int* value, int min, int max, const std::string& help);
  void AddDouble(const std::string& name, double* value, const std::string& help);
  void AddString(const std::string& name, std::string* value, const std::string& help);
  // A flag sets *value = true; `--no-NAME` sets it to false.
  void AddFlag(const std::string& name, bool* value, const std::string& help);
  // An option whose text `set` converts itself (and throws std::invalid_argument on nonsense, naming the
  // option); `default_text` is what --help shows.
  void AddCustom(const std::string& name, const std::string& default_text, const std::string& help,
                 std::function<void(const std::string&)> set);

  // Options added from now on belong to `group` (initially ""): a command running several stages asks
  // for the settings of each stage's group.
  void SetGroup(std::string group) { group_ = std::move(group); }
  // Name -> value text (as given on the command line or in the config file, else the default; flags "on"
  // or "off") of every option of `group`.
  std::map<std::string, std::string> Settings(const std::string& group) const;

  // Parses argv[first..argc) (after the options of the --config file, if one is given). Returns false when
  // --help was asked for (help has been printed on stdout). Throws std::invalid_argument on any error; an
  // error in the config file names the file and line.
  bool Parse(int argc, char** argv, int first);

  std::string Help() const;

  // Stages word option errors with field names (lib/util/option_error.h). A field is shown as the flag
  // of its last component with '_' as '-' ("calibration.grid.z_far" as --z-far) when this parser has
  // that option, as the flag named here when the names differ, and as itself otherwise.
  void NameField(const std::string& field, const std::string& option);
  std::string FlagOf(const std::string& field) const;
  // Runs `work`; an OptionError it throws is rethrown as std::invalid_argument worded with the flags.
  void RunWithFlags(const std::function<void()>& work) const;

 private:
  struct Option {
    std::string name;
    std::string help;
    std::string default_text;
    bool required = false;
    bool is_flag = false;
    bool is_path = false;
    bool seen = false;
    std::function<void(const std::string&)> set;
    std::string group;
    std::string text;  // the value as given
  };
  void Add(const std::string& name, const std::string& help, const std::string& default_text,
           std::function<void(const std::string&)> set);
  Option& Find(const std::string& name);
  // Applies `--NAME[=VALUE]` (name without dashes; `value` used when the option takes one and has none).
  void Apply(std::string argument, const std::function<std::string(const std::string&)>& next_value,
             const std::filesystem::path& relative_to);
  void ReadConfigFile(const std::filesystem::path& path);

  std::string usage_;
  std::string summary_;
  std::string group_;
  std::vector<Option> options_;
  std::map<std::string, std::string> option_of_field_;
};

}  // namespace lutex
