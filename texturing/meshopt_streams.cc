#include "texturing/meshopt_streams.h"

#include <stdexcept>
#include <string>

#include <meshoptimizer.h>

namespace lutex {

std::vector<unsigned char> EncodeMeshoptAttributes(const void* data, std::size_t count, std::size_t stride) {
  if (stride == 0 || stride % 4 != 0 || stride > 256) {
    throw std::invalid_argument("EXT_meshopt_compression: a vertex stride of " + std::to_string(stride) +
                                " bytes (it must be a multiple of 4, at most 256)");
  }
  std::vector<unsigned char> bytes(meshopt_encodeVertexBufferBound(count, stride));
  bytes.resize(meshopt_encodeVertexBuffer(bytes.data(), bytes.size(), data, count, stride));
  return bytes;
}

std::vector<unsigned char> EncodeMeshoptTriangles(const std::vector<std::uint32_t>& indices, std::size_t vertex_count) {
  if (indices.size() % 3 != 0) throw std::invalid_argument("EXT_meshopt_compression: a triangle list of " +
                                                           std::to_string(indices.size()) + " indices");
  std::vector<unsigned char> bytes(meshopt_encodeIndexBufferBound(indices.size(), vertex_count));
  bytes.resize(meshopt_encodeIndexBuffer(bytes.data(), bytes.size(), indices.data(), indices.size()));
  return bytes;
}

}  // namespace lutex
