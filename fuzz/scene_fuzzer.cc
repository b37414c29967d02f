// Scene descriptions of lutex simulate (lib/model/scene_description.h). The reader only names the mesh and
// texture files; it does not open them.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/model/scene_description.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("scene.json", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadSceneDescription(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
