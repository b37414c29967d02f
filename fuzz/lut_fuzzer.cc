// LUT files, versions 1 to 3 (lib/lut/lut_file.h).

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/lut/lut_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("lut.lut", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadLut(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
