#include "colmap_integration/cli/dive_options.h"

namespace lutex {

void AddDiveOptions(OptionParser& parser, std::filesystem::path* workspace, std::filesystem::path* mesh) {
  parser.AddPath("workspace", workspace, "COLMAP workspace (images/, sparse/0 or sparse/).", true);
  parser.AddPath("mesh", mesh, "Mesh of W's scene in the model's world frame (.ply, .obj, .off, .stl).", true);
}

void AddThreadsOption(OptionParser& parser, int* num_threads) {
  parser.AddInt("num-threads", num_threads, "Threads; 0 = all cores. Results do not depend on it.");
}

}  // namespace lutex
