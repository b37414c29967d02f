#include "lib/util/json_fields.h"

#include <cmath>
#include <cstdint>
#include <set>

namespace lutex {

using nlohmann::json;

namespace {

// "where.key", or "key" for a key of the document's top level (where is empty).
std::string KeyPath(const std::string& where, const std::string& key) {
  return where.empty() ? key : where + "." + key;
}

}  // namespace

void ExpectKeys(const json& object, const std::string& where, std::initializer_list<const char*> allowed) {
  if (!object.is_object()) throw JsonFieldError((where.empty() ? "the file" : where) + " must be a JSON object");
  const std::set<std::string> known(allowed.begin(), allowed.end());
  for (const auto& item : object.items()) {
    if (known.count(item.key()) == 0) throw JsonFieldError("unknown key " + KeyPath(where, item.key()));
  }
}

double NumberField(const json& object, const std::string& key, const std::string& where, double fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_number()) throw JsonFieldError(KeyPath(where, key) + " must be a number");
  return object[key].get<double>();
}

long long WholeNumber(const json& value, const std::string& what, long long min, long long max) {
  const auto fail = [&] {
    return JsonFieldError(what + " must be a whole number from " + std::to_string(min) + " to " + std::to_string(max));
  };
  if (value.is_number_integer()) {  // exact, whatever its size
    if (value.is_number_unsigned()) {
      const auto number = value.get<std::uint64_t>();
      if (max < 0 || number > static_cast<std::uint64_t>(max) || static_cast<long long>(number) < min) throw fail();
      return static_cast<long long>(number);
    }
    const auto number = value.get<std::int64_t>();
    if (number < min || number > max) throw fail();
    return number;
  }
  if (!value.is_number()) throw fail();
  const double number = value.get<double>();
  // 0x1p63: a max near 2^63 rounds up as a double, and 2^63 itself has no long long.
  if (!(number >= static_cast<double>(min) && number <= static_cast<double>(max) && number < 0x1p63) ||
      number != std::floor(number)) {
    throw fail();
  }
  return static_cast<long long>(number);
}

long long IntegerField(const json& object, const std::string& key, const std::string& where, long long fallback,
                       long long min, long long max) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_number()) throw JsonFieldError(KeyPath(where, key) + " must be a number");
  return WholeNumber(object[key], KeyPath(where, key), min, max);
}

std::string TextField(const json& object, const std::string& key, const std::string& where,
                      const std::string& fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_string()) throw JsonFieldError(KeyPath(where, key) + " must be a string");
  return object[key].get<std::string>();
}

Eigen::Vector3d Vector3Field(const json& object, const std::string& key, const std::string& where,
                             const Eigen::Vector3d& fallback) {
  if (!object.contains(key)) return fallback;
  const json& value = object[key];
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number()) {
    throw JsonFieldError(KeyPath(where, key) + " must be an array of 3 numbers");
  }
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

std::string JsonErrorText(const std::exception& error) {
  const std::string text = error.what();
  if (dynamic_cast<const nlohmann::json::parse_error*>(&error) != nullptr) {
    // "[json.exception.parse_error.101] parse error at line 1, column 15: syntax error while ..."
    const std::size_t at = text.find("at line ");
    const std::size_t end = text.find(':', at == std::string::npos ? 0 : at);
    if (at == std::string::npos || end == std::string::npos) return "not valid JSON";
    return "not valid JSON (" + text.substr(at + 3, end - at - 3) + ")";
  }
  if (dynamic_cast<const nlohmann::json::exception*>(&error) != nullptr) {
    const std::size_t tag_end = text.find("] ");
    return tag_end == std::string::npos ? text : text.substr(tag_end + 2);
  }
  return text;
}

}  // namespace lutex
