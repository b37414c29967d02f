#pragma once

// The options every command over a dive registers the same way, stated once.

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "colmap_integration/cli/option_parser.h"

namespace lutex {

// --workspace W (a COLMAP workspace) and --mesh M (its scene in the model's world frame), both required.
void AddDiveOptions(OptionParser& parser, std::filesystem::path* workspace, std::filesystem::path* mesh);

// --num-threads N: 0 (all cores) or 1 to 4 per core; anything else is refused.
void AddThreadsOption(OptionParser& parser, int* num_threads);

// --memory-limit MiB: the stage refuses to start when its memory estimate exceeds it (default 0: the
// machine's available memory).
void AddMemoryLimitOption(OptionParser& parser, std::size_t* bytes);

// --image-cache MiB: decoded images kept for the next tiles, into every one of `bytes` (lutex run sets
// the mosaic's and the tiles' budget with one option); 0 = none.
void AddImageCacheOption(OptionParser& parser, std::initializer_list<std::size_t*> bytes);

// Parses a positive number of MiB ("512", "1.5") for `flag`; throws std::invalid_argument otherwise.
std::size_t ParseMebibytes(const std::string& flag, const std::string& text);

}  // namespace lutex
