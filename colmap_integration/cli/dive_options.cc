#include "colmap_integration/cli/dive_options.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace lutex {

void AddDiveOptions(OptionParser& parser, std::filesystem::path* workspace, std::filesystem::path* mesh) {
  parser.AddPath("workspace", workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("mesh", mesh, "Mesh of W's scene in the model's world frame (.ply, .obj, .off, .stl).", true);
}

void AddThreadsOption(OptionParser& parser, int* num_threads) {
  // More threads than 4 per core only cost memory (each holds an image's buffers); a negative count is a typo.
  const int most = 4 * static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  parser.AddIntInRange("num-threads", num_threads, 0, most,
                       "Threads; 0 = all cores, at most " + std::to_string(most) +
                           " (4 per core). Results do not depend on it.");
}

std::size_t ParseMebibytes(const std::string& flag, const std::string& text) {
  double mib = 0.0;
  std::size_t used = 0;
  try {
    mib = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(mib >= 1.0) || !(mib < 1e12)) {
    throw std::invalid_argument("--" + flag + " must be a number of MiB, at least 1, not '" + text + "'");
  }
  return static_cast<std::size_t>(mib * 1024.0 * 1024.0);
}

void AddImageCacheOption(OptionParser& parser, std::initializer_list<std::size_t*> bytes) {
  const std::vector<std::size_t*> targets(bytes);
  parser.AddCustom("image-cache", std::to_string(*targets.front() >> 20),
                   "MiB of decoded images and confidence maps kept for the next tiles of 3D Tiles and the\n"
                   "      mosaic: a view is read once per tile that sees it, and neighbouring tiles see mostly\n"
                   "      the same views (384 MiB holds ten 12 MP 8-bit images; a 16-bit restored image takes\n"
                   "      twice as much, its confidence map as much as an 8-bit image). 0 = none: least\n"
                   "      memory, most decoding.",
                   [targets](const std::string& text) {
                     const std::size_t value = text == "0" ? 0 : ParseMebibytes("image-cache", text);
                     for (std::size_t* target : targets) *target = value;
                   });
}

void AddMemoryLimitOption(OptionParser& parser, std::size_t* bytes) {
  parser.AddCustom("memory-limit", "0",
                   "MiB the command may use; it estimates what it needs from the cameras, the mesh and the\n"
                   "      options before it starts and refuses, saying so, what would not fit. 0 (default) = the\n"
                   "      machine's available memory.",
                   [bytes](const std::string& text) { *bytes = text == "0" ? 0 : ParseMebibytes("memory-limit", text); });
}

}  // namespace lutex
