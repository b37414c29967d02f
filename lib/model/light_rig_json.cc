#include "lib/model/light_rig_json.h"

#include <cmath>
#include <string>

#include "lib/util/json_fields.h"

namespace lutex {

using nlohmann::json;

namespace {

Light ParseLight(const json& object, const std::string& where) {
  ExpectKeys(object, where, {"name", "position", "direction", "intensity", "power_W", "profile", "exponent",
                             "sigma_deg", "spot_size_deg", "spot_blend"});
  Light light;
  light.name = TextField(object, "name", where, where);
  light.position_in_cam = Vector3Field(object, "position", where, Eigen::Vector3d::Zero());
  light.direction_in_cam = Vector3Field(object, "direction", where, Eigen::Vector3d::UnitZ()).normalized();
  if (object.contains("power_W")) {
    // Cycles: a light of power P has on-axis radiant intensity P / (4 pi).
    light.intensity = Eigen::Vector3d::Constant(NumberField(object, "power_W", where, 0.0) / (4.0 * M_PI));
  }
  light.intensity = Vector3Field(object, "intensity", where, light.intensity);
  const std::string profile = TextField(object, "profile", where, "isotropic");
  const std::optional<BeamProfile> known = BeamProfileFromName(profile);
  if (!known) {
    throw JsonFieldError(where + ".profile '" + profile + "' is not isotropic, cosine_power, gaussian or cycles_spot");
  }
  light.profile = *known;
  switch (light.profile) {
    case BeamProfile::kIsotropic: break;
    case BeamProfile::kCosinePower: light.exponent = NumberField(object, "exponent", where, 1.0); break;
    case BeamProfile::kGaussian:
      light.sigma_rad = NumberField(object, "sigma_deg", where, 30.0) * M_PI / 180.0;
      break;
    case BeamProfile::kCyclesSpot:
      light.spot_size_rad = NumberField(object, "spot_size_deg", where, 110.0) * M_PI / 180.0;
      light.spot_blend = NumberField(object, "spot_blend", where, 0.5);
      break;
  }
  if ((light.intensity.array() < 0).any()) throw JsonFieldError(where + ".intensity must not be negative");
  return light;
}

}  // namespace

LightRig ParseLightRig(const json& root) {
  if (!root.contains("lights") || !root["lights"].is_array() || root["lights"].empty()) {
    throw JsonFieldError("needs at least one light in lights[]");
  }
  LightRig rig;
  for (std::size_t i = 0; i < root["lights"].size(); ++i) {
    rig.lights.push_back(ParseLight(root["lights"][i], "lights[" + std::to_string(i) + "]"));
  }
  return rig;
}

json LightRigToJson(const LightRig& rig) {
  json lights = json::array();
  for (const Light& light : rig.lights) {
    json object = {{"position", {light.position_in_cam.x(), light.position_in_cam.y(), light.position_in_cam.z()}},
                   {"direction", {light.direction_in_cam.x(), light.direction_in_cam.y(), light.direction_in_cam.z()}},
                   {"intensity", {light.intensity.x(), light.intensity.y(), light.intensity.z()}},
                   {"profile", BeamProfileName(light.profile)}};
    if (!light.name.empty()) object["name"] = light.name;
    switch (light.profile) {
      case BeamProfile::kIsotropic: break;
      case BeamProfile::kCosinePower: object["exponent"] = light.exponent; break;
      case BeamProfile::kGaussian: object["sigma_deg"] = light.sigma_rad * 180.0 / M_PI; break;
      case BeamProfile::kCyclesSpot:
        object["spot_size_deg"] = light.spot_size_rad * 180.0 / M_PI;
        object["spot_blend"] = light.spot_blend;
        break;
    }
    lights.push_back(object);
  }
  return lights;
}

LightRig ReadLightRig(const std::filesystem::path& path) {
  return ReadJsonFile(path, "light rig", [](const json& root, const std::filesystem::path&) {
    return ParseLightRig(root);
  });
}

}  // namespace lutex
