#pragma once

// Typed fields of the JSON files lutex reads (scene descriptions, light rigs): every accessor names the key
// path of what is wrong ("lights[1].profile must be a string"), objects refuse unknown keys so a typo never
// passes silently, and ReadJsonFile puts the file's name in front of every error. For the readers' .cc
// files only: it speaks nlohmann::json.

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace lutex {

// An error inside a JSON document, worded with the key path; ReadJsonFile adds the file.
struct JsonFieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `where` is the key path of `object` in its document ("lights[1]"), empty for the top level of a file whose
// keys need no prefix. Every error names the path of the offending key.
// Throws JsonFieldError when `object` is not an object or has a key outside `allowed`.
void ExpectKeys(const nlohmann::json& object, const std::string& where, std::initializer_list<const char*> allowed);

// object[key] as a number, string or 3-vector; `fallback` when the key is absent, JsonFieldError when it has
// another type.
double NumberField(const nlohmann::json& object, const std::string& key, const std::string& where, double fallback);
// `value` as a whole number in [min, max], else JsonFieldError "`what` must be a whole number from min to max".
// Use it instead of the JSON library's get<int>(), which casts any number (1e30 too: undefined behaviour).
long long WholeNumber(const nlohmann::json& value, const std::string& what, long long min, long long max);
// object[key] as a whole number in [min, max]; `fallback` when the key is absent, JsonFieldError when it is
// not a number, not whole or out of range (a count or size read as double must not be cast blindly).
long long IntegerField(const nlohmann::json& object, const std::string& key, const std::string& where,
                       long long fallback, long long min, long long max);
std::string TextField(const nlohmann::json& object, const std::string& key, const std::string& where,
                      const std::string& fallback);
Eigen::Vector3d Vector3Field(const nlohmann::json& object, const std::string& key, const std::string& where,
                             const Eigen::Vector3d& fallback);

// The text of an error from parsing or reading JSON, in lutex's words: a syntax error becomes "not valid
// JSON (line 3, column 15)", the library's type and key errors lose its "[json.exception...]" tag. Other
// errors keep their text.
std::string JsonErrorText(const std::exception& error);

// `parse(root, folder of the file)` of the JSON in `path`; every error (missing file, syntax, types, the
// parser's own) is rethrown as std::runtime_error starting with the path. `what` names the kind of file
// ("scene description") in the missing-file error.
template <typename Parse>
auto ReadJsonFile(const std::filesystem::path& path, const char* what, Parse parse)
    -> decltype(parse(nlohmann::json(), path)) {
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error(path.string() + ": no such " + what);
  try {
    return parse(nlohmann::json::parse(stream), path.parent_path());
  } catch (const std::exception& error) {  // JSON syntax and type errors, and the parser's own
    throw std::runtime_error(path.string() + ": " + JsonErrorText(error));
  }
}

}  // namespace lutex
