// Light rig files of lutex calibrate --shading-rig and the lights of scene descriptions
// (lib/model/light_rig_json.h).

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/model/light_rig_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("rig.json", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadLightRig(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
