#include "tests/support/shared_datasets.h"

namespace lutex::testing {

namespace fs = std::filesystem;

std::optional<fs::path> SharedDevDatasets() {
  const fs::path dev = fs::path(LUTEX_SHARED_DATASETS) / "dev";
  if (fs::is_directory(dev)) return dev;
  return std::nullopt;
}

}  // namespace lutex::testing
