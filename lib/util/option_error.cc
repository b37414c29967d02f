#include "lib/util/option_error.h"

namespace lutex {

namespace {

std::string Substitute(const std::string& message, const std::function<std::string(const std::string&)>& name_of) {
  std::string text;
  std::size_t at = 0;
  while (at < message.size()) {
    const std::size_t open = message.find('{', at);
    const std::size_t close = open == std::string::npos ? std::string::npos : message.find('}', open);
    if (close == std::string::npos) break;
    text += message.substr(at, open - at) + name_of(message.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return text + message.substr(at);
}

}  // namespace

OptionError::OptionError(const std::string& message)
    : std::invalid_argument(Substitute(message, [](const std::string& field) { return field; })),
      message_(message) {}

std::string OptionError::Render(const std::function<std::string(const std::string&)>& name_of) const {
  return Substitute(message_, name_of);
}

}  // namespace lutex
