// Georeference files, W/georef.json (lib/geo/georeference.h).

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/geo/georeference.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("georef.json", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadGeoreference(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
