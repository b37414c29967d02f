#pragma once

// Where the shared Blender Cycles datasets are (../shared/datasets, see their README; the build sets
// LUTEX_SHARED_DATASETS). Tests that need them skip with a message when they are absent.

#include <filesystem>
#include <optional>

namespace lutex::testing {

// The dev/ folder of the shared datasets, or nothing when it is absent.
std::optional<std::filesystem::path> SharedDevDatasets();

}  // namespace lutex::testing
