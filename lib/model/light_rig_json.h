#pragma once

// Light rigs in JSON, as in scene descriptions (README, 'Scene descriptions') and the rig files of
// `lutex calibrate --shading-rig`:
//
//   "lights": [{"position": [-0.4, 0, 0], "direction": [0, 0, 1],       camera frame, metres; axis (any length)
//               "intensity": [1, 1, 1]  or  "power_W": 15,              on-axis radiant intensity; Cycles power
//               "profile": "isotropic" | "cosine_power" (exponent) | "gaussian" (sigma_deg) |
//                          "cycles_spot" (spot_size_deg, spot_blend),
//               "name": "port"}]

#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "lib/model/light_rig.h"

namespace lutex {

// The rig of root["lights"] (other keys of `root` are ignored). Throws JsonFieldError (json_fields.h)
// naming the key path, e.g. "lights[1].profile", when there is no light or a light is malformed.
LightRig ParseLightRig(const nlohmann::json& root);

// The rig of the "lights" array of a JSON file (a scene description, or a file with only {"lights": [...]}).
// Throws std::runtime_error naming the file and the key.
LightRig ReadLightRig(const std::filesystem::path& path);

// The rig as the "lights" array ParseLightRig reads back (intensity per channel, the profile's own keys).
nlohmann::json LightRigToJson(const LightRig& rig);

}  // namespace lutex
