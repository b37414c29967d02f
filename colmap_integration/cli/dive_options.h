#pragma once

// The options every command over a dive registers the same way, stated once.

#include <filesystem>

#include "colmap_integration/cli/option_parser.h"

namespace lutex {

// --workspace W (a COLMAP workspace) and --mesh M (its scene in the model's world frame), both required.
void AddDiveOptions(OptionParser& parser, std::filesystem::path* workspace, std::filesystem::path* mesh);

// --num-threads N: 0 (all cores) or 1 to 4 per core; anything else is refused.
void AddThreadsOption(OptionParser& parser, int* num_threads);

}  // namespace lutex
