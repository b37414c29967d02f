#pragma once

// The bridge between stream parsers/writers and files (STYLE.md: readers take a stream and a path).
// ParseFile opens `path`, runs the stream parser and prefixes any error with the file name.
// WriteFileAtomically runs the stream writer on a temporary file and renames it into place only when
// everything was written.

#include <cerrno>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "lib/util/atomic_output.h"
#include "lib/util/write_failure.h"

namespace lutex {

template <typename Parser>
auto ParseFile(const std::filesystem::path& path, std::ios::openmode mode, Parser&& parse) {
  std::ifstream stream(path, mode);
  if (!stream) {
    throw std::runtime_error(path.string() + (std::filesystem::exists(path) ? ": cannot open the file"
                                                                             : ": no such file"));
  }
  try {
    return parse(stream);
  } catch (const std::exception& error) {
    throw std::runtime_error(path.string() + ": " + error.what());
  }
}

// A failure to create or write the file (a full disk above all) is reported naming `path`
// (write_failure.h).
template <typename Writer>
void WriteFileAtomically(const std::filesystem::path& path, std::ios::openmode mode, Writer&& write) {
  AtomicOutputFile output(path);
  {
    errno = 0;
    std::ofstream stream(output.temporary_path(), mode);
    if (!stream) throw std::runtime_error(DescribeWriteFailure(path, errno, "cannot create the file"));
    write(stream);
    stream.close();
    if (!stream) throw std::runtime_error(DescribeWriteFailure(path, errno, "writing failed"));
  }
  output.Commit();
}

// Writes `size` bytes from `data` to `path` the same way.
inline void WriteBytesAtomically(const std::filesystem::path& path, const void* data, std::size_t size) {
  WriteFileAtomically(path, std::ios::binary, [&](std::ostream& stream) {
    stream.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  });
}

}  // namespace lutex
