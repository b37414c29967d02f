#include "lib/model/scene_description.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "lib/geometry/look_at.h"
#include "lib/model/light_rig_json.h"
#include "lib/util/json_fields.h"

namespace lutex {
namespace {

using nlohmann::json;

std::vector<NamedPose> ParseSurvey(const json& object) {
  ExpectKeys(object, "survey", {"pattern", "x", "y", "lines", "images_per_line", "altitude"});
  if (TextField(object, "pattern", "survey", "lawnmower") != "lawnmower") {
    throw JsonFieldError("survey.pattern must be lawnmower");
  }
  const auto range = [&object](const char* key, double low, double high) {
    if (!object.contains(key)) return std::pair<double, double>(low, high);
    const json& value = object[key];
    if (!value.is_array() || value.size() != 2) throw JsonFieldError(std::string("survey.") + key + " must be [min, max]");
    return std::pair<double, double>(value[0].get<double>(), value[1].get<double>());
  };
  const auto [x_min, x_max] = range("x", -3.5, 3.5);
  const auto [y_min, y_max] = range("y", -1.5, 1.5);
  // At most kMaxSurveyImages images: a survey is simulated in memory, and a typo must not ask for billions.
  constexpr long long kMaxSurveyImages = 100000;
  const int lines = static_cast<int>(IntegerField(object, "lines", "survey", 3, 1, kMaxSurveyImages));
  const int per_line = static_cast<int>(IntegerField(object, "images_per_line", "survey", 8, 1, kMaxSurveyImages));
  const double altitude = NumberField(object, "altitude", "survey", 2.0);
  if (!(altitude > 0)) throw JsonFieldError("survey needs altitude > 0");
  if (static_cast<long long>(lines) * per_line > kMaxSurveyImages) {
    throw JsonFieldError("survey.lines x survey.images_per_line must be at most " + std::to_string(kMaxSurveyImages));
  }
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

// "mesh": a file (relative to the description) or a synthetic seafloor; absent: the default seafloor.
void ParseMesh(const json& root, const std::filesystem::path& folder, SceneDescription* scene) {
  if (root.contains("mesh") && root["mesh"].is_string()) {
    scene->mesh_path = folder / root["mesh"].get<std::string>();
  } else if (root.contains("mesh")) {
    ExpectKeys(root["mesh"], "mesh", {"synthetic"});
    if (!root["mesh"].contains("synthetic")) throw JsonFieldError("mesh must be a file name or {\"synthetic\": {...}}");
    const json& synthetic = root["mesh"]["synthetic"];
    ExpectKeys(synthetic, "mesh.synthetic", {"size", "cell_size", "relief", "boulders", "patch_size", "seed"});
    if (synthetic.contains("size")) {
      scene->seafloor.size_x = synthetic["size"].at(0).get<double>();
      scene->seafloor.size_y = synthetic["size"].at(1).get<double>();
    }
    scene->seafloor.cell_size = NumberField(synthetic, "cell_size", "mesh.synthetic", scene->seafloor.cell_size);
    scene->seafloor.relief = NumberField(synthetic, "relief", "mesh.synthetic", scene->seafloor.relief);
    scene->seafloor.num_boulders = static_cast<int>(
        IntegerField(synthetic, "boulders", "mesh.synthetic", scene->seafloor.num_boulders, 0, 1000000));
    scene->seafloor.patch_size = NumberField(synthetic, "patch_size", "mesh.synthetic", scene->seafloor.patch_size);
    scene->seafloor.seed = static_cast<std::uint32_t>(
        IntegerField(synthetic, "seed", "mesh.synthetic", scene->seafloor.seed, 0, 4294967295LL));
  }
}

// "albedo": where the surface colour comes from.
void ParseAlbedo(const json& root, const std::filesystem::path& folder, SceneDescription* scene) {
  if (root.contains("albedo")) {
    const json& albedo = root["albedo"];
    if (albedo.is_string()) {
      if (albedo.get<std::string>() == "face_colors") {
        scene->albedo_kind = SceneDescription::AlbedoKind::kFaceColors;
      } else if (albedo.get<std::string>() != "vertex_colors") {
        throw JsonFieldError("albedo must be \"vertex_colors\", \"face_colors\" or an object");
      }
    } else {
      ExpectKeys(albedo, "albedo", {"constant", "texture", "encoding"});
      if (albedo.contains("constant")) {
        scene->albedo_kind = SceneDescription::AlbedoKind::kConstant;
        scene->constant_albedo = Vector3Field(albedo, "constant", "albedo", scene->constant_albedo);
      } else if (albedo.contains("texture")) {
        scene->albedo_kind = SceneDescription::AlbedoKind::kTexture;
        scene->texture_path = folder / TextField(albedo, "texture", "albedo", "");
        scene->texture_encoding = ParseImageEncoding(TextField(albedo, "encoding", "albedo", "linear16"));
      } else {
        throw JsonFieldError("albedo needs constant or texture");
      }
    }
  }
}

// "camera": required; checked against its model.
void ParseCamera(const json& root, SceneDescription* scene) {
  if (!root.contains("camera")) throw JsonFieldError("the scene needs a camera");
  const json& camera = root["camera"];
  ExpectKeys(camera, "camera", {"model", "width", "height", "params"});
  scene->camera.camera_id = 1;
  scene->camera.model_id = CameraModelIdFromName(TextField(camera, "model", "camera", "PINHOLE"));
  const auto side = [&camera](const char* key) {  // Camera::Check words 0 and too large; this keeps the cast defined
    return static_cast<std::uint64_t>(IntegerField(camera, key, "camera", 0, 0, 1LL << 53));
  };
  scene->camera.width = side("width");
  scene->camera.height = side("height");
  if (!camera.contains("params") || !camera["params"].is_array()) throw JsonFieldError("camera.params must be an array");
  for (const json& value : camera["params"]) scene->camera.params.push_back(value.get<double>());
  scene->camera.Check("camera");
}

// "poses" (explicit cam_from_world) or "survey" (a lawnmower pattern); at least one pose.
void ParsePoses(const json& root, SceneDescription* scene) {
  if (root.contains("poses")) {
    for (std::size_t i = 0; i < root["poses"].size(); ++i) {
      const json& pose = root["poses"][i];
      const std::string where = "poses[" + std::to_string(i) + "]";
      ExpectKeys(pose, where, {"name", "qvec", "tvec"});
      if (!pose.contains("qvec") || pose["qvec"].size() != 4) throw JsonFieldError(where + ".qvec must be [w, x, y, z]");
      const Eigen::Quaterniond q(pose["qvec"][0].get<double>(), pose["qvec"][1].get<double>(),
                                 pose["qvec"][2].get<double>(), pose["qvec"][3].get<double>());
      scene->poses.push_back({TextField(pose, "name", where, "frame_" + std::to_string(i) + ".png"),
                             Rigid3d(q.normalized(), Vector3Field(pose, "tvec", where, Eigen::Vector3d::Zero()))});
    }
  } else {
    scene->poses = ParseSurvey(root.contains("survey") ? root["survey"] : json::object());
  }
  if (scene->poses.empty()) throw JsonFieldError("the scene has no poses");
}

// "water": "air" (the default, no medium) or absorption, scattering and g.
void ParseWater(const json& root, SceneDescription* scene) {
  if (root.contains("water") && !(root["water"].is_string() && root["water"].get<std::string>() == "air")) {
    const json& water = root["water"];
    ExpectKeys(water, "water", {"absorption", "scattering", "g", "description"});
    scene->water.absorption = Vector3Field(water, "absorption", "water", Eigen::Vector3d::Zero());
    scene->water.scattering = Vector3Field(water, "scattering", "water", Eigen::Vector3d::Zero());
    scene->water.anisotropy_g = NumberField(water, "g", "water", 0.9);
    if ((scene->water.absorption.array() < 0).any() || (scene->water.scattering.array() < 0).any() ||
        std::abs(scene->water.anisotropy_g) >= 1.0) {
      throw JsonFieldError("water needs non-negative coefficients and |g| < 1");
    }
  }
}

// "sensor": exposure, blur and noise.
void ParseSensor(const json& root, SceneDescription* scene) {
  if (root.contains("sensor")) {
    const json& sensor = root["sensor"];
    ExpectKeys(sensor, "sensor", {"exposure", "exposure_variation", "blur_px", "shot_noise", "read_noise", "seed"});
    scene->sensor.exposure = NumberField(sensor, "exposure", "sensor", 1.0);
    scene->sensor.exposure_variation = NumberField(sensor, "exposure_variation", "sensor", 0.0);
    scene->sensor.blur_sigma_px = NumberField(sensor, "blur_px", "sensor", 0.0);
    scene->sensor.shot_noise = NumberField(sensor, "shot_noise", "sensor", 0.0);
    scene->sensor.read_noise = NumberField(sensor, "read_noise", "sensor", 0.0);
    scene->sensor.seed = static_cast<std::uint64_t>(IntegerField(sensor, "seed", "sensor", 1, 0, 1LL << 53));
    scene->sensor.Check();
  }
}

// "output": image encoding and sparse model format.
void ParseOutput(const json& root, SceneDescription* scene) {
  if (root.contains("output")) {
    const json& output = root["output"];
    ExpectKeys(output, "output", {"encoding", "sparse_format", "sparse_points", "sparse_point_noise"});
    const double points = NumberField(output, "sparse_points", "output", 0.0);
    if (!(points >= 0.0 && points <= 1e6) || points != std::floor(points)) {
      throw JsonFieldError("output.sparse_points must be a whole number from 0 to 1000000");
    }
    scene->sparse_points_per_image = static_cast<int>(points);
    scene->sparse_point_noise = NumberField(output, "sparse_point_noise", "output", 0.0);
    if (!(scene->sparse_point_noise >= 0.0 && scene->sparse_point_noise < 1.0)) {
      throw JsonFieldError("output.sparse_point_noise must be in [0, 1) metres");
    }
    scene->output_encoding = ParseImageEncoding(TextField(output, "encoding", "output", "srgb8"));
    if (scene->output_encoding == ImageEncoding::kFloat) throw JsonFieldError("output.encoding must be srgb8 or linear16");
    const std::string format = TextField(output, "sparse_format", "output", "text");
    if (format != "text" && format != "binary") throw JsonFieldError("output.sparse_format must be text or binary");
    scene->sparse_format = format == "text" ? SparseFormat::kText : SparseFormat::kBinary;
  }
}

// "lut": the grid of the true LUT written beside the images; sized to the camera.
void ParseLutGrid(const json& root, SceneDescription* scene) {
  const json lut = root.contains("lut") ? root["lut"] : json::object();
  ExpectKeys(lut, "lut", {"nx", "ny", "nz", "z_near", "z_far", "spacing"});
  scene->lut_grid.nx = static_cast<int>(IntegerField(lut, "nx", "lut", 40, 1, 4096));
  scene->lut_grid.ny = static_cast<int>(IntegerField(lut, "ny", "lut", 30, 1, 4096));
  scene->lut_grid.nz = static_cast<int>(IntegerField(lut, "nz", "lut", 10, 1, 4096));
  scene->lut_grid.z_near = NumberField(lut, "z_near", "lut", 0.5);
  scene->lut_grid.z_far = NumberField(lut, "z_far", "lut", 5.0);
  const std::string spacing = TextField(lut, "spacing", "lut", "inverse_z");
  if (spacing != "z" && spacing != "inverse_z") throw JsonFieldError("lut.spacing must be z or inverse_z");
  scene->lut_grid.spacing = spacing == "z" ? DepthSpacing::kUniformZ : DepthSpacing::kUniformInverseZ;
  scene->lut_grid.image_width = static_cast<int>(scene->camera.width);
  scene->lut_grid.image_height = static_cast<int>(scene->camera.height);
  scene->lut_grid.Check();
}

// "simulator": backscatter integration, shadows and forward scattering.
void ParseSimulator(const json& root, SceneDescription* scene) {
  if (root.contains("simulator")) {
    const json& simulator = root["simulator"];
    ExpectKeys(simulator, "simulator", {"backscatter_steps", "max_range", "shadows", "forward_scatter"});
    scene->simulator.backscatter_steps =
        static_cast<int>(IntegerField(simulator, "backscatter_steps", "simulator", 96, 1, 100000));
    scene->simulator.max_range = NumberField(simulator, "max_range", "simulator", 30.0);
    if (simulator.contains("shadows")) scene->simulator.shadows = simulator["shadows"].get<bool>();
    if (simulator.contains("forward_scatter")) scene->simulator.forward_scatter = simulator["forward_scatter"].get<bool>();
    scene->simulator.Check();
  }
}

SceneDescription Parse(const json& root, const std::filesystem::path& folder) {
  ExpectKeys(root, "scene", {"mesh", "albedo", "camera", "survey", "poses", "lights", "water", "sensor", "output", "lut",
                             "simulator", "comment"});
  SceneDescription scene;
  ParseMesh(root, folder, &scene);
  ParseAlbedo(root, folder, &scene);
  ParseCamera(root, &scene);
  ParsePoses(root, &scene);
  scene.rig = ParseLightRig(root);
  ParseWater(root, &scene);
  ParseSensor(root, &scene);
  ParseOutput(root, &scene);
  ParseLutGrid(root, &scene);
  ParseSimulator(root, &scene);
  return scene;
}

}  // namespace

SceneDescription ReadSceneDescription(const std::filesystem::path& path) {
  return ReadJsonFile(path, "scene description", Parse);
}

}  // namespace lutex
