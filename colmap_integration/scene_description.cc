#include "colmap_integration/scene_description.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lib/geometry/look_at.h"

namespace lutex {
namespace {

using nlohmann::json;

// Errors inside the description name the key path, e.g. "lights[1].profile".
struct DescriptionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void ExpectKeys(const json& object, const std::string& where, std::initializer_list<const char*> allowed) {
  if (!object.is_object()) throw DescriptionError(where + " must be an object");
  const std::set<std::string> known(allowed.begin(), allowed.end());
  for (const auto& item : object.items()) {
    if (known.count(item.key()) == 0) throw DescriptionError("unknown key " + where + "." + item.key());
  }
}

double Number(const json& object, const std::string& key, const std::string& where, double fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_number()) throw DescriptionError(where + "." + key + " must be a number");
  return object[key].get<double>();
}

Eigen::Vector3d Vector3(const json& object, const std::string& key, const std::string& where,
                        const Eigen::Vector3d& fallback) {
  if (!object.contains(key)) return fallback;
  const json& value = object[key];
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() || !value[2].is_number()) {
    throw DescriptionError(where + "." + key + " must be an array of 3 numbers");
  }
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

std::string Text(const json& object, const std::string& key, const std::string& where, const std::string& fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_string()) throw DescriptionError(where + "." + key + " must be a string");
  return object[key].get<std::string>();
}

Light ParseLight(const json& object, const std::string& where) {
  ExpectKeys(object, where, {"name", "position", "direction", "intensity", "power_W", "profile", "exponent",
                             "sigma_deg", "spot_size_deg", "spot_blend"});
  Light light;
  light.name = Text(object, "name", where, where);
  light.position_in_cam = Vector3(object, "position", where, Eigen::Vector3d::Zero());
  light.direction_in_cam = Vector3(object, "direction", where, Eigen::Vector3d::UnitZ()).normalized();
  if (object.contains("power_W")) {
    // Cycles: a light of power P has on-axis radiant intensity P / (4 pi).
    light.intensity = Eigen::Vector3d::Constant(Number(object, "power_W", where, 0.0) / (4.0 * M_PI));
  }
  light.intensity = Vector3(object, "intensity", where, light.intensity);
  const std::string profile = Text(object, "profile", where, "isotropic");
  const std::optional<BeamProfile> known = BeamProfileFromName(profile);
  if (!known) {
    throw DescriptionError(where + ".profile '" + profile +
                           "' is not isotropic, cosine_power, gaussian or cycles_spot");
  }
  light.profile = *known;
  switch (light.profile) {
    case BeamProfile::kIsotropic: break;
    case BeamProfile::kCosinePower: light.exponent = Number(object, "exponent", where, 1.0); break;
    case BeamProfile::kGaussian: light.sigma_rad = Number(object, "sigma_deg", where, 30.0) * M_PI / 180.0; break;
    case BeamProfile::kCyclesSpot:
      light.spot_size_rad = Number(object, "spot_size_deg", where, 110.0) * M_PI / 180.0;
      light.spot_blend = Number(object, "spot_blend", where, 0.5);
      break;
  }
  if ((light.intensity.array() < 0).any()) throw DescriptionError(where + ".intensity must not be negative");
  return light;
}

std::vector<NamedPose> ParseSurvey(const json& object) {
  ExpectKeys(object, "survey", {"pattern", "x", "y", "lines", "images_per_line", "altitude"});
  if (Text(object, "pattern", "survey", "lawnmower") != "lawnmower") {
    throw DescriptionError("survey.pattern must be lawnmower");
  }
  const auto range = [&object](const char* key, double low, double high) {
    if (!object.contains(key)) return std::pair<double, double>(low, high);
    const json& value = object[key];
    if (!value.is_array() || value.size() != 2) throw DescriptionError(std::string("survey.") + key + " must be [min, max]");
    return std::pair<double, double>(value[0].get<double>(), value[1].get<double>());
  };
  const auto [x_min, x_max] = range("x", -3.5, 3.5);
  const auto [y_min, y_max] = range("y", -1.5, 1.5);
  const int lines = static_cast<int>(Number(object, "lines", "survey", 3));
  const int per_line = static_cast<int>(Number(object, "images_per_line", "survey", 8));
  const double altitude = Number(object, "altitude", "survey", 2.0);
  if (lines < 1 || per_line < 1 || !(altitude > 0)) throw DescriptionError("survey needs lines, images_per_line >= 1 and altitude > 0");
  std::vector<NamedPose> poses;
  for (int line = 0; line < lines; ++line) {
    for (int step = 0; step < per_line; ++step) {
      // Lines along x, alternating direction; the camera looks straight down, image "down" along -y.
      const int along = line % 2 == 0 ? step : per_line - 1 - step;
      const double x = per_line == 1 ? x_min : x_min + (x_max - x_min) * along / (per_line - 1);
      const double y = lines == 1 ? y_min : y_min + (y_max - y_min) * line / (lines - 1);
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%04zu.png", poses.size());
      poses.push_back({name, CamFromWorldLookingAt(Eigen::Vector3d(x, y, altitude), Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(0, -1, 0))});
    }
  }
  return poses;
}

LightRig ParseLights(const json& root) {
  if (!root.contains("lights") || !root["lights"].is_array() || root["lights"].empty()) {
    throw DescriptionError("needs at least one light in lights[]");
  }
  LightRig rig;
  for (std::size_t i = 0; i < root["lights"].size(); ++i) {
    rig.lights.push_back(ParseLight(root["lights"][i], "lights[" + std::to_string(i) + "]"));
  }
  return rig;
}

SceneDescription Parse(const json& root, const std::filesystem::path& folder) {
  ExpectKeys(root, "scene", {"mesh", "albedo", "camera", "survey", "poses", "lights", "water", "sensor", "output", "lut",
                             "simulator", "comment"});
  SceneDescription scene;
  if (root.contains("mesh") && root["mesh"].is_string()) {
    scene.mesh_path = folder / root["mesh"].get<std::string>();
  } else if (root.contains("mesh")) {
    ExpectKeys(root["mesh"], "mesh", {"synthetic"});
    const json& synthetic = root["mesh"]["synthetic"];
    ExpectKeys(synthetic, "mesh.synthetic", {"size", "cell_size", "relief", "boulders", "patch_size", "seed"});
    if (synthetic.contains("size")) {
      scene.seafloor.size_x = synthetic["size"].at(0).get<double>();
      scene.seafloor.size_y = synthetic["size"].at(1).get<double>();
    }
    scene.seafloor.cell_size = Number(synthetic, "cell_size", "mesh.synthetic", scene.seafloor.cell_size);
    scene.seafloor.relief = Number(synthetic, "relief", "mesh.synthetic", scene.seafloor.relief);
    scene.seafloor.num_boulders = static_cast<int>(Number(synthetic, "boulders", "mesh.synthetic", scene.seafloor.num_boulders));
    scene.seafloor.patch_size = Number(synthetic, "patch_size", "mesh.synthetic", scene.seafloor.patch_size);
    scene.seafloor.seed = static_cast<std::uint32_t>(Number(synthetic, "seed", "mesh.synthetic", scene.seafloor.seed));
  }

  if (root.contains("albedo")) {
    const json& albedo = root["albedo"];
    if (albedo.is_string()) {
      if (albedo.get<std::string>() == "face_colors") {
        scene.albedo_kind = SceneDescription::AlbedoKind::kFaceColors;
      } else if (albedo.get<std::string>() != "vertex_colors") {
        throw DescriptionError("albedo must be \"vertex_colors\", \"face_colors\" or an object");
      }
    } else {
      ExpectKeys(albedo, "albedo", {"constant", "texture", "encoding"});
      if (albedo.contains("constant")) {
        scene.albedo_kind = SceneDescription::AlbedoKind::kConstant;
        scene.constant_albedo = Vector3(albedo, "constant", "albedo", scene.constant_albedo);
      } else if (albedo.contains("texture")) {
        scene.albedo_kind = SceneDescription::AlbedoKind::kTexture;
        scene.texture_path = folder / Text(albedo, "texture", "albedo", "");
        scene.texture_encoding = ParseImageEncoding(Text(albedo, "encoding", "albedo", "linear16"));
      } else {
        throw DescriptionError("albedo needs constant or texture");
      }
    }
  }

  if (!root.contains("camera")) throw DescriptionError("the scene needs a camera");
  const json& camera = root["camera"];
  ExpectKeys(camera, "camera", {"model", "width", "height", "params"});
  scene.camera.camera_id = 1;
  scene.camera.model_id = CameraModelIdFromName(Text(camera, "model", "camera", "PINHOLE"));
  scene.camera.width = static_cast<std::uint64_t>(Number(camera, "width", "camera", 0));
  scene.camera.height = static_cast<std::uint64_t>(Number(camera, "height", "camera", 0));
  if (!camera.contains("params") || !camera["params"].is_array()) throw DescriptionError("camera.params must be an array");
  for (const json& value : camera["params"]) scene.camera.params.push_back(value.get<double>());
  scene.camera.Check("camera");

  if (root.contains("poses")) {
    for (std::size_t i = 0; i < root["poses"].size(); ++i) {
      const json& pose = root["poses"][i];
      const std::string where = "poses[" + std::to_string(i) + "]";
      ExpectKeys(pose, where, {"name", "qvec", "tvec"});
      if (!pose.contains("qvec") || pose["qvec"].size() != 4) throw DescriptionError(where + ".qvec must be [w, x, y, z]");
      const Eigen::Quaterniond q(pose["qvec"][0].get<double>(), pose["qvec"][1].get<double>(),
                                 pose["qvec"][2].get<double>(), pose["qvec"][3].get<double>());
      scene.poses.push_back({Text(pose, "name", where, "frame_" + std::to_string(i) + ".png"),
                             Rigid3d(q.normalized(), Vector3(pose, "tvec", where, Eigen::Vector3d::Zero()))});
    }
  } else {
    scene.poses = ParseSurvey(root.contains("survey") ? root["survey"] : json::object());
  }
  if (scene.poses.empty()) throw DescriptionError("the scene has no poses");

  scene.rig = ParseLights(root);

  if (root.contains("water") && !(root["water"].is_string() && root["water"].get<std::string>() == "air")) {
    const json& water = root["water"];
    ExpectKeys(water, "water", {"absorption", "scattering", "g", "description"});
    scene.water.absorption = Vector3(water, "absorption", "water", Eigen::Vector3d::Zero());
    scene.water.scattering = Vector3(water, "scattering", "water", Eigen::Vector3d::Zero());
    scene.water.anisotropy_g = Number(water, "g", "water", 0.9);
    if ((scene.water.absorption.array() < 0).any() || (scene.water.scattering.array() < 0).any() ||
        std::abs(scene.water.anisotropy_g) >= 1.0) {
      throw DescriptionError("water needs non-negative coefficients and |g| < 1");
    }
  }

  if (root.contains("sensor")) {
    const json& sensor = root["sensor"];
    ExpectKeys(sensor, "sensor", {"exposure", "blur_px", "shot_noise", "read_noise", "seed"});
    scene.sensor.exposure = Number(sensor, "exposure", "sensor", 1.0);
    scene.sensor.blur_sigma_px = Number(sensor, "blur_px", "sensor", 0.0);
    scene.sensor.shot_noise = Number(sensor, "shot_noise", "sensor", 0.0);
    scene.sensor.read_noise = Number(sensor, "read_noise", "sensor", 0.0);
    scene.sensor.seed = static_cast<std::uint64_t>(Number(sensor, "seed", "sensor", 1));
    scene.sensor.Check();
  }
  if (root.contains("output")) {
    const json& output = root["output"];
    ExpectKeys(output, "output", {"encoding", "sparse_format"});
    scene.output_encoding = ParseImageEncoding(Text(output, "encoding", "output", "srgb8"));
    if (scene.output_encoding == ImageEncoding::kFloat) throw DescriptionError("output.encoding must be srgb8 or linear16");
    const std::string format = Text(output, "sparse_format", "output", "text");
    if (format != "text" && format != "binary") throw DescriptionError("output.sparse_format must be text or binary");
    scene.sparse_format = format == "text" ? SparseFormat::kText : SparseFormat::kBinary;
  }
  const json lut = root.contains("lut") ? root["lut"] : json::object();
  ExpectKeys(lut, "lut", {"nx", "ny", "nz", "z_near", "z_far", "spacing"});
  scene.lut_grid.nx = static_cast<int>(Number(lut, "nx", "lut", 40));
  scene.lut_grid.ny = static_cast<int>(Number(lut, "ny", "lut", 30));
  scene.lut_grid.nz = static_cast<int>(Number(lut, "nz", "lut", 10));
  scene.lut_grid.z_near = Number(lut, "z_near", "lut", 0.5);
  scene.lut_grid.z_far = Number(lut, "z_far", "lut", 5.0);
  const std::string spacing = Text(lut, "spacing", "lut", "inverse_z");
  if (spacing != "z" && spacing != "inverse_z") throw DescriptionError("lut.spacing must be z or inverse_z");
  scene.lut_grid.spacing = spacing == "z" ? DepthSpacing::kUniformZ : DepthSpacing::kUniformInverseZ;
  scene.lut_grid.image_width = static_cast<int>(scene.camera.width);
  scene.lut_grid.image_height = static_cast<int>(scene.camera.height);
  scene.lut_grid.Check();
  if (root.contains("simulator")) {
    const json& simulator = root["simulator"];
    ExpectKeys(simulator, "simulator", {"backscatter_steps", "max_range", "shadows"});
    scene.simulator.backscatter_steps = static_cast<int>(Number(simulator, "backscatter_steps", "simulator", 96));
    scene.simulator.max_range = Number(simulator, "max_range", "simulator", 30.0);
    if (simulator.contains("shadows")) scene.simulator.shadows = simulator["shadows"].get<bool>();
    scene.simulator.Check();
  }
  return scene;
}

// `parse` applied to the JSON in `path`; every error names the file.
template <typename Parsed>
Parsed ParseJsonFile(const std::filesystem::path& path, const char* what, Parsed (*parse)(const json&, const std::filesystem::path&)) {
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error(path.string() + ": no such " + what);
  try {
    return parse(json::parse(stream), path.parent_path());
  } catch (const std::exception& error) {  // JSON syntax and type errors, and the parser's own
    throw std::runtime_error(path.string() + ": " + error.what());
  }
}

}  // namespace

SceneDescription ReadSceneDescription(const std::filesystem::path& path) {
  return ParseJsonFile<SceneDescription>(path, "scene description", Parse);
}

LightRig ReadLightRig(const std::filesystem::path& path) {
  return ParseJsonFile<LightRig>(path, "light rig", [](const json& root, const std::filesystem::path&) {
    return ParseLights(root);
  });
}

}  // namespace lutex
