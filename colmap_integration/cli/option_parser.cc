#include "colmap_integration/cli/option_parser.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "lib/util/logging.h"
#include "lib/util/option_error.h"

namespace lutex {

OptionParser::OptionParser(std::string usage, std::string summary)
    : usage_(std::move(usage)), summary_(std::move(summary)) {
  AddCustom("log-level", "info", "Messages on stderr: debug, info, warning, error or silent.",
            [](const std::string& text) { SetLogLevel(ParseLogLevel(text)); });
}

namespace {

// Parses all of `text` with `convert` (std::stoi, std::stod), or throws naming the option and the value.
template <typename T, typename Convert>
T ParseNumber(const std::string& name, const std::string& text, const char* kind, Convert convert) {
  std::size_t used = 0;
  T result{};
  try {
    result = convert(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) {
    throw std::invalid_argument("--" + name + " expects " + kind + ", not '" + text + "'");
  }
  return result;
}

// `text` without leading and trailing blanks.
std::string Trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return std::string();
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace

void OptionParser::Add(const std::string& name, const std::string& help, const std::string& default_text,
                       std::function<void(const std::string&)> set) {
  Option option;
  option.name = name;
  option.help = help;
  option.default_text = default_text;
  option.set = std::move(set);
  option.group = group_;
  options_.push_back(std::move(option));
}

void OptionParser::AddPath(const std::string& name, std::filesystem::path* value, const std::string& help,
                           bool required) {
  Add(name, help, value->string(), [value](const std::string& text) { *value = text; });
  options_.back().required = required;
  options_.back().is_path = true;
}

void OptionParser::AddInt(const std::string& name, int* value, const std::string& help) {
  Add(name, help, std::to_string(*value), [value, name](const std::string& text) {
    *value = ParseNumber<int>(name, text, "a whole number",
                              [](const std::string& t, std::size_t* used) { return std::stoi(t, used); });
  });
}

void OptionParser::AddIntInRange(const std::string& name, int* value, int min, int max, const std::string& help) {
  Add(name, help, std::to_string(*value), [value, name, min, max](const std::string& text) {
    const int parsed = ParseNumber<int>(name, text, "a whole number",
                                        [](const std::string& t, std::size_t* used) { return std::stoi(t, used); });
    if (parsed < min || parsed > max) {
      throw std::invalid_argument("--" + name + " must be from " + std::to_string(min) + " to " + std::to_string(max) +
                                  ", not " + text);
    }
    *value = parsed;
  });
}

void OptionParser::AddDouble(const std::string& name, double* value, const std::string& help) {
  std::ostringstream shown;
  shown << *value;
  Add(name, help, shown.str(), [value, name](const std::string& text) {
    *value = ParseNumber<double>(name, text, "a number",
                                 [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
  });
}

void OptionParser::AddString(const std::string& name, std::string* value, const std::string& help) {
  Add(name, help, *value, [value](const std::string& text) { *value = text; });
}

void OptionParser::AddFlag(const std::string& name, bool* value, const std::string& help) {
  Add(name, help, *value ? "on" : "off", [value](const std::string& text) { *value = text == "true"; });
  options_.back().is_flag = true;
}

void OptionParser::AddCustom(const std::string& name, const std::string& default_text, const std::string& help,
                             std::function<void(const std::string&)> set) {
  Add(name, help, default_text, std::move(set));
}

OptionParser::Option& OptionParser::Find(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return option;
  }
  throw std::invalid_argument("unknown option --" + name + " (see --help)");
}

void OptionParser::Apply(std::string argument, const std::function<std::string(const std::string&)>& next_value,
                         const std::filesystem::path& relative_to) {
  std::string value;
  bool has_value = false;
  if (const auto equals = argument.find('='); equals != std::string::npos) {
    value = argument.substr(equals + 1);
    argument = argument.substr(0, equals);
    has_value = true;
  }
  bool negated = false;
  if (argument.rfind("no-", 0) == 0) {
    for (const Option& option : options_) negated |= option.is_flag && option.name == argument.substr(3);
  }
  Option& option = Find(negated ? argument.substr(3) : argument);
  if (option.is_flag) {
    if (has_value) throw std::invalid_argument("--" + option.name + " is a flag and takes no value");
    option.set(negated ? "false" : "true");
    option.text = negated ? "off" : "on";
  } else {
    if (!has_value) value = next_value(option.name);
    // "mesh =" in a config file (or --mesh=) says nothing; taken as given it would read as "--mesh is
    // required" or an empty path far from the line that caused it.
    if (Trimmed(value).empty()) throw std::invalid_argument("--" + option.name + " has an empty value");
    if (option.is_path && !relative_to.empty() && !value.empty() && std::filesystem::path(value).is_relative()) {
      value = (relative_to / value).lexically_normal().string();
    }
    option.set(value);
    option.text = value;
  }
  option.seen = true;
}

std::map<std::string, std::string> OptionParser::Settings(const std::string& group) const {
  std::map<std::string, std::string> settings;
  for (const Option& option : options_) {
    if (option.group == group) settings[option.name] = option.seen ? option.text : option.default_text;
  }
  return settings;
}

void OptionParser::ReadConfigFile(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("--config: cannot read " + path.string());
  const std::filesystem::path folder = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    line = Trimmed(line);
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("--", 0) == 0) line = line.substr(2);
    std::string argument = line;
    if (const auto equals = line.find('='); equals != std::string::npos) {
      argument = Trimmed(line.substr(0, equals)) + "=" + Trimmed(line.substr(equals + 1));
    }
    try {
      if (argument.rfind("config=", 0) == 0) throw std::invalid_argument("a config file cannot name another");
      Apply(argument, [](const std::string& name) -> std::string {
        throw std::invalid_argument("--" + name + " needs a value (name = value)");
      }, folder);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(path.string() + ":" + std::to_string(number) + ": " + error.what());
    }
  }
}

bool OptionParser::Parse(int argc, char** argv, int first) {
  // The config file first, so that the command line wins.
  for (int i = first; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--help" || argument == "-h") {
      std::cout << Help();
      return false;
    }
    if (argument == "--config") {
      if (i + 1 >= argc) throw std::invalid_argument("--config needs a value");
      ReadConfigFile(argv[i + 1]);
    } else if (argument.rfind("--config=", 0) == 0) {
      ReadConfigFile(argument.substr(9));
    }
  }
  for (int i = first; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument '" + argument + "' (see --help)");
    if (argument == "--config") {
      ++i;
      continue;
    }
    if (argument.rfind("--config=", 0) == 0) continue;
    Apply(argument.substr(2), [&](const std::string& name) -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("--" + name + " needs a value");
      return argv[++i];
    }, {});
  }
  for (const Option& option : options_) {
    if (option.required && !option.seen) throw std::invalid_argument("--" + option.name + " is required (see --help)");
  }
  return true;
}

std::string OptionParser::Help() const {
  std::ostringstream out;
  out << "Usage: " << usage_ << "\n\n" << summary_ << "\n\nOptions:\n";
  // The options every command has (the first, --log-level, is registered by the constructor) come last.
  std::vector<const Option*> ordered;
  for (std::size_t i = 1; i < options_.size(); ++i) ordered.push_back(&options_[i]);
  ordered.push_back(&options_.front());
  for (const Option* listed : ordered) {
    const Option& option = *listed;
    out << "  --" << option.name << (option.is_flag ? "" : " VALUE");
    if (option.required) {
      out << "  (required)";
    } else if (!option.default_text.empty()) {
      out << "  (default: " << option.default_text << ")";
    }
    out << "\n      " << option.help << "\n";
  }
  out << "  --config FILE\n      Read options from FILE: one per line, 'name = value' or a flag's name; '#' starts a\n"
         "      comment; relative paths are relative to FILE's folder; the command line wins.\n"
         "  --help\n      Show this help.\n";
  return out.str();
}

void OptionParser::NameField(const std::string& field, const std::string& option) { option_of_field_[field] = option; }

std::string OptionParser::FlagOf(const std::string& field) const {
  if (const auto named = option_of_field_.find(field); named != option_of_field_.end()) return "--" + named->second;
  std::string name = field.substr(field.rfind('.') + 1);
  std::replace(name.begin(), name.end(), '_', '-');
  for (const Option& option : options_) {
    if (option.name == name) return "--" + name;
  }
  return field;
}

void OptionParser::RunWithFlags(const std::function<void()>& work) const {
  try {
    work();
  } catch (const OptionError& error) {
    throw std::invalid_argument(error.Render([this](const std::string& field) { return FlagOf(field); }));
  }
}

}  // namespace lutex
