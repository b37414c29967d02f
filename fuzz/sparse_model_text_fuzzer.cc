// COLMAP's text sparse model (colmap_integration/io/sparse_model_text.h) read as a whole folder, so
// that the checks across files (SparseModel::Check) are fuzzed too. The input is cameras.txt, images.txt
// and points3D.txt joined by kFuzzFileSeparator; files the input lacks are absent from the folder.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "colmap_integration/io/sparse_model_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path folder = lutex::WriteFuzzFolder(
      "sparse", lutex::FuzzBytes(data, size), {"cameras.txt", "images.txt", "points3D.txt"});
  try {
    lutex::ReadSparseModel(folder);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
