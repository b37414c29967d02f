#pragma once

// Little-endian binary reading and writing of plain values, as COLMAP's binary formats use them.
// Reads throw std::runtime_error("truncated ...") when the stream ends early.

#include <cstdint>
#include <istream>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lutex {

// Throws std::runtime_error("truncated file: it ends inside <what>"): what a reader of a binary file says
// when the file ends before a value it holds (or a count it gives) does.
[[noreturn]] inline void ThrowTruncated(const std::string& what) {
  throw std::runtime_error("truncated file: it ends inside " + what);
}

template <typename T>
T ReadBinary(std::istream& stream, const char* what) {
  static_assert(std::is_trivially_copyable<T>::value, "plain values only");
  T value;
  stream.read(reinterpret_cast<char*>(&value), sizeof(T));
  if (stream.gcount() != static_cast<std::streamsize>(sizeof(T))) ThrowTruncated(what);
  return value;
}

// The bytes from the stream's position to its end, or nothing when the stream cannot seek (a pipe). Readers
// check a count read from a file against it before allocating, so a corrupt count fails as a truncated
// file instead of reserving gigabytes. A stream that has already met its end (a header line with no
// newline after it) has none left; tellg would fail there and say nothing.
inline std::optional<std::uint64_t> BytesLeft(std::istream& stream) {
  if (stream.eof()) return 0;
  const std::istream::pos_type here = stream.tellg();
  if (here == std::istream::pos_type(-1)) return std::nullopt;
  stream.seekg(0, std::ios::end);
  const std::istream::pos_type end = stream.tellg();
  stream.seekg(here);
  if (end == std::istream::pos_type(-1) || !stream || end < here) {
    stream.clear();
    stream.seekg(here);
    return std::nullopt;
  }
  return static_cast<std::uint64_t>(end - here);
}

template <typename T>
void WriteBinary(std::ostream& stream, const T& value) {
  static_assert(std::is_trivially_copyable<T>::value, "plain values only");
  stream.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

// An array of plain values (Eigen's fixed-size vectors included: their bytes are their coefficients, though
// Eigen does not declare them trivially copyable),
// after its count (uint64), in the machine's own byte order: for scratch files read back by the process
// that wrote them.
template <typename T>
void WriteBinaryArray(std::ostream& stream, const std::vector<T>& values) {
  WriteBinary(stream, static_cast<std::uint64_t>(values.size()));
  stream.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}

// Reads what WriteBinaryArray wrote into `values`; ThrowTruncated(what) when the stream holds fewer values
// than its count says (checked before allocating).
template <typename T>
void ReadBinaryArray(std::istream& stream, const char* what, std::vector<T>& values) {
  const auto count = ReadBinary<std::uint64_t>(stream, what);
  if (count > BytesLeft(stream).value_or(0) / sizeof(T)) ThrowTruncated(what);
  values.resize(count);
  stream.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(count * sizeof(T)));
  if (!stream) ThrowTruncated(what);
}

}  // namespace lutex
