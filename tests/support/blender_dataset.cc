#include "tests/support/blender_dataset.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"

namespace lutex::testing {

namespace fs = std::filesystem;

BlenderDataset LoadBlenderDataset(const fs::path& root) {
  std::ifstream stream(root / "metadata.json");
  if (!stream) throw std::runtime_error((root / "metadata.json").string() + ": missing");
  const nlohmann::json metadata = nlohmann::json::parse(stream);
  BlenderDataset dataset;
  dataset.root = root;
  dataset.kind = metadata.at("kind").get<std::string>();
  dataset.model = ReadSparseModel(root / "sparse" / "0");
  if (dataset.kind != "purewater") dataset.mesh = ReadMesh(root / "scene" / "mesh.ply");
  for (const auto& entry : metadata.at("light_rig").at("lights")) {
    Light light;
    light.name = entry.at("name").get<std::string>();
    const auto& position = entry.at("position_cam");
    light.position_in_cam = Eigen::Vector3d(position[0], position[1], position[2]);
    const auto& direction = entry.at("direction_cam");
    light.direction_in_cam = Eigen::Vector3d(direction[0], direction[1], direction[2]).normalized();
    // Cycles: on-axis radiant intensity P / (4 pi) (metadata units_and_profile).
    light.intensity = Eigen::Vector3d::Constant(entry.at("power_W").get<double>() / (4.0 * M_PI));
    if (entry.at("type").get<std::string>() == "SPOT") {
      light.profile = BeamProfile::kCyclesSpot;
      light.spot_size_rad = entry.at("spot_size_deg").get<double>() * M_PI / 180.0;
      light.spot_blend = entry.at("spot_blend").get<double>();
    }
    dataset.rig.lights.push_back(light);
  }
  const auto& water = metadata.at("water");
  if (!water.is_null()) {
    const auto& a = water.at("absorption_per_m");
    const auto& b = water.at("scattering_per_m");
    dataset.water.absorption = Eigen::Vector3d(a[0], a[1], a[2]);
    dataset.water.scattering = Eigen::Vector3d(b[0], b[1], b[2]);
    dataset.water.anisotropy_g = water.at("anisotropy_g").get<double>();
  }
  return dataset;
}

}  // namespace lutex::testing
