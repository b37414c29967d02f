#pragma once

// The small simulated survey the command tests share: the bundled clear-water scene cut down to a
// 4 x 3 m seafloor of 0.1 m cells (2400 faces) seen by 6 images of 160 x 120 (two lawnmower lines of
// three at 2 m altitude), a scene description for `lutex simulate`.

#include <nlohmann/json.hpp>

namespace lutex::testing {

nlohmann::json SmallSurveyScene();

}  // namespace lutex::testing
