#include "colmap_integration/cli/dive_options.h"

#include <algorithm>
#include <string>
#include <thread>

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

}  // namespace lutex
