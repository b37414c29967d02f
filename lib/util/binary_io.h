#pragma once

// Little-endian binary reading and writing of plain values, as COLMAP's binary formats use them.
// Reads throw std::runtime_error("truncated ...") when the stream ends early.

#include <cstdint>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace lutex {

template <typename T>
T ReadBinary(std::istream& stream, const char* what) {
  static_assert(std::is_trivially_copyable<T>::value, "plain values only");
  T value;
  stream.read(reinterpret_cast<char*>(&value), sizeof(T));
  if (stream.gcount() != static_cast<std::streamsize>(sizeof(T))) {
    throw std::runtime_error(std::string("truncated file: it ends inside ") + what);
  }
  return value;
}

template <typename T>
void WriteBinary(std::ostream& stream, const T& value) {
  static_assert(std::is_trivially_copyable<T>::value, "plain values only");
  stream.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace lutex
