#include "colmap_integration/option_parser.h"

#include <iostream>
#include <sstream>
#include <stdexcept>

namespace lutex {

OptionParser::OptionParser(std::string usage, std::string summary)
    : usage_(std::move(usage)), summary_(std::move(summary)) {}

void OptionParser::AddPath(const std::string& name, std::filesystem::path* value, const std::string& help,
                           bool required) {
  options_.push_back({name, help, value->empty() ? "" : value->string(), required, false, false,
                      [value](const std::string& text) { *value = text; }});
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

}  // namespace

void OptionParser::AddInt(const std::string& name, int* value, const std::string& help) {
  options_.push_back({name, help, std::to_string(*value), false, false, false, [value, name](const std::string& text) {
                        *value = ParseNumber<int>(name, text, "a whole number",
                                                  [](const std::string& t, std::size_t* used) { return std::stoi(t, used); });
                      }});
}

void OptionParser::AddDouble(const std::string& name, double* value, const std::string& help) {
  std::ostringstream shown;
  shown << *value;
  options_.push_back({name, help, shown.str(), false, false, false, [value, name](const std::string& text) {
                        *value = ParseNumber<double>(name, text, "a number",
                                                     [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
                      }});
}

void OptionParser::AddString(const std::string& name, std::string* value, const std::string& help) {
  options_.push_back({name, help, *value, false, false, false, [value](const std::string& text) { *value = text; }});
}

void OptionParser::AddFlag(const std::string& name, bool* value, const std::string& help) {
  options_.push_back({name, help, *value ? "on" : "off", false, true, false,
                      [value](const std::string& text) { *value = text == "true"; }});
}

OptionParser::Option& OptionParser::Find(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return option;
  }
  throw std::invalid_argument("unknown option --" + name + " (see --help)");
}

bool OptionParser::Parse(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i) {
    std::string argument = argv[i];
    if (argument == "--help" || argument == "-h") {
      std::cout << Help();
      return false;
    }
    if (argument.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument '" + argument + "' (see --help)");
    argument = argument.substr(2);
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
    } else {
      if (!has_value) {
        if (i + 1 >= argc) throw std::invalid_argument("--" + option.name + " needs a value");
        value = argv[++i];
      }
      option.set(value);
    }
    option.seen = true;
  }
  for (const Option& option : options_) {
    if (option.required && !option.seen) throw std::invalid_argument("--" + option.name + " is required (see --help)");
  }
  return true;
}

std::string OptionParser::Help() const {
  std::ostringstream out;
  out << "Usage: " << usage_ << "\n\n" << summary_ << "\n\nOptions:\n";
  for (const Option& option : options_) {
    out << "  --" << option.name << (option.is_flag ? "" : " VALUE");
    if (option.required) {
      out << "  (required)";
    } else if (!option.default_text.empty()) {
      out << "  (default: " << option.default_text << ")";
    }
    out << "\n      " << option.help << "\n";
  }
  out << "  --help\n      Show this help.\n";
  return out.str();
}

}  // namespace lutex
