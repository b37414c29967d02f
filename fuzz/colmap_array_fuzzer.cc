// COLMAP's dense arrays, depth and normal maps (colmap_integration/io/colmap_array.h).

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "colmap_integration/io/colmap_array.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("depth_map.bin", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadColmapArray(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
