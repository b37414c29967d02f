// PLY meshes (lib/geometry/ply_io.h), through ReadMesh, which also checks the vertices and indices.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/geometry/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("mesh.ply", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadMesh(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
