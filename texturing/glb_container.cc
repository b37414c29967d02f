#include "texturing/glb_container.h"

#include <cstdint>
#include <limits>
#include <stdexcept>

namespace lutex {

namespace {

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

std::size_t Padded(std::size_t size) { return (size + 3) / 4 * 4; }

void WriteWord(std::ostream& stream, std::uint32_t word) {
  const unsigned char bytes[4] = {static_cast<unsigned char>(word), static_cast<unsigned char>(word >> 8),
                                  static_cast<unsigned char>(word >> 16), static_cast<unsigned char>(word >> 24)};
  stream.write(reinterpret_cast<const char*>(bytes), 4);
}

void WriteChunk(std::ostream& stream, std::uint32_t type, const char* data, std::size_t size, char padding) {
  WriteWord(stream, static_cast<std::uint32_t>(Padded(size)));
  WriteWord(stream, type);
  stream.write(data, static_cast<std::streamsize>(size));
  for (std::size_t i = size; i < Padded(size); ++i) stream.put(padding);
}

}  // namespace

void WriteGlb(std::ostream& stream, const std::string& json, const std::vector<unsigned char>& bin) {
  const std::size_t length = 12 + 8 + Padded(json.size()) + (bin.empty() ? 0 : 8 + Padded(bin.size()));
  if (length > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("a GLB file holds at most 4 GiB; this model needs " + std::to_string(length >> 20) +
                                " MiB (use a larger texel size, or lutex tiles)");
  }
  WriteWord(stream, kMagic);
  WriteWord(stream, kVersion);
  WriteWord(stream, static_cast<std::uint32_t>(length));
  WriteChunk(stream, kJsonChunk, json.data(), json.size(), ' ');
  if (!bin.empty()) WriteChunk(stream, kBinChunk, reinterpret_cast<const char*>(bin.data()), bin.size(), '\0');
  if (!stream) throw std::runtime_error("writing the GLB failed");
}

}  // namespace lutex
