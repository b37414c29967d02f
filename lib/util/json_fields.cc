#include "lib/util/json_fields.h"

#include <set>

namespace lutex {

using nlohmann::json;

void ExpectKeys(const json& object, const std::string& where, std::initializer_list<const char*> allowed) {
  if (!object.is_object()) throw JsonFieldError(where + " must be an object");
  const std::set<std::string> known(allowed.begin(), allowed.end());
  for (const auto& item : object.items()) {
    if (known.count(item.key()) == 0) throw JsonFieldError("unknown key " + where + "." + item.key());
  }
}

double NumberField(const json& object, const std::string& key, const std::string& where, double fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_number()) throw JsonFieldError(where + "." + key + " must be a number");
  return object[key].get<double>();
}

std::string TextField(const json& object, const std::string& key, const std::string& where,
                      const std::string& fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_string()) throw JsonFieldError(where + "." + key + " must be a string");
  return object[key].get<std::string>();
}

Eigen::Vector3d Vector3Field(const json& object, const std::string& key, const std::string& where,
                             const Eigen::Vector3d& fallback) {
  if (!object.contains(key)) return fallback;
  const json& value = object[key];
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number()) {
    throw JsonFieldError(where + "." + key + " must be an array of 3 numbers");
  }
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

}  // namespace lutex
