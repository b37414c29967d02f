#pragma once

// The binary glTF container (glTF 2.0 spec, section 4.4 "GLB File Format Specification"): a 12-byte header
// (magic "glTF", version 2, total length), a JSON chunk padded with spaces to 4 bytes, and a BIN chunk
// (buffer 0) padded with zeros, all little-endian.
//
// lutex writes the container itself rather than through tinygltf: tinygltf 2.7 copies the whole binary
// buffer once more before writing it (a 12 MP model's PNG pages are hundreds of MB), and it writes neither
// buffer nor buffer-view extensions, which EXT_meshopt_compression needs (meshopt_streams.h).

#include <ostream>
#include <string>
#include <vector>

namespace lutex {

// Writes `json` (the glTF JSON, whose buffers[0] has no uri and byteLength == bin.size()) and `bin`. The
// BIN chunk is left out when `bin` is empty, as the spec asks. Throws std::runtime_error when the stream
// fails, std::invalid_argument when the file would exceed the format's 4 GiB.
void WriteGlb(std::ostream& stream, const std::string& json, const std::vector<unsigned char>& bin);

}  // namespace lutex
