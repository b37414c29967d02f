#include "tests/support/small_survey.h"

#include <filesystem>
#include <fstream>

namespace lutex::testing {

nlohmann::json SmallSurveyScene() {
  nlohmann::json scene = nlohmann::json::parse(
      std::ifstream(std::filesystem::path(LUTEX_SOURCE_DIR) / "examples" / "scenes" / "clear_two_lights.json"));
  scene["mesh"]["synthetic"]["size"] = {4, 3};
  scene["mesh"]["synthetic"]["cell_size"] = 0.1;
  scene["camera"]["width"] = 160;
  scene["camera"]["height"] = 120;
  scene["camera"]["params"] = {80, 80, 80, 60};
  scene["survey"] = {{"pattern", "lawnmower"}, {"x", {-1, 1}}, {"y", {-0.5, 0.5}}, {"lines", 2},
                     {"images_per_line", 3}, {"altitude", 2.0}};
  return scene;
}

}  // namespace lutex::testing
