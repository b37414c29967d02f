#pragma once

// The bridge between stream parsers/writers and files (STYLE.md: readers take a stream and a path).
// ParseFile opens `path`, runs the stream parser and prefixes any error with the file name.
// WriteFileAtomically runs the stream writer on a temporary file and renames it into place only when
// everything was written.

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "lib/util/atomic_output.h"

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

template <typename Writer>
void WriteFileAtomically(const std::filesystem::path& path, std::ios::openmode mode, Writer&& write) {
  AtomicOutputFile output(path);
  {
    std::ofstream stream(output.temporary_path(), mode);
    if (!stream) throw std::runtime_error(path.string() + ": cannot create the file");
    write(stream);
    stream.flush();
    if (!stream) throw std::runtime_error(path.string() + ": writing failed (disk full?)");
  }
  output.Commit();
}

}  // namespace lutex
