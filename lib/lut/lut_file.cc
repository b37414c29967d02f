#include "lib/lut/lut_file.h"

#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "lib/util/binary_io.h"
#include "lib/util/file_streams.h"
#include "lib/util/json_fields.h"

namespace lutex {
namespace {

constexpr const char* kMagic = "LUTEX-LUT 1";
constexpr const char* kMagicWithRig = "LUTEX-LUT 2";
// Version 3 records the forward scattering restoration must take out; a lutex that reads only 1 and 2
// refuses it instead of restoring without.
constexpr const char* kMagicWithForwardScatter = "LUTEX-LUT 3";
constexpr const char* kLayout = "slab k, then row j, then column i; per node alpha_r alpha_g alpha_b beta_r beta_g beta_b";

nlohmann::json LightToJson(const Light& light) {
  const auto vector = [](const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  return {{"position", vector(light.position_in_cam)}, {"direction", vector(light.direction_in_cam)},
          {"intensity", vector(light.intensity)}, {"profile", BeamProfileName(light.profile)},
          {"exponent", light.exponent}, {"sigma_rad", light.sigma_rad},
          {"spot_size_rad", light.spot_size_rad}, {"spot_blend", light.spot_blend}};
}

Light LightFromJson(const nlohmann::json& object) {
  const auto vector = [&](const char* key) {
    const nlohmann::json& v = object.at(key);
    return Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
  };
  Light light;
  light.position_in_cam = vector("position");
  light.direction_in_cam = vector("direction");
  light.intensity = vector("intensity");
  const std::string profile = object.at("profile").get<std::string>();
  const std::optional<BeamProfile> known = BeamProfileFromName(profile);
  if (!known) throw std::runtime_error("unknown light profile '" + profile + "' in shading_rig");
  light.profile = *known;
  light.exponent = object.at("exponent").get<double>();
  light.sigma_rad = object.at("sigma_rad").get<double>();
  light.spot_size_rad = object.at("spot_size_rad").get<double>();
  light.spot_blend = object.at("spot_blend").get<double>();
  return light;
}

}  // namespace

FrustumLut ReadLut(std::istream& stream) {
  std::string line;
  if (!std::getline(stream, line) || line.rfind("LUTEX-LUT", 0) != 0) {
    throw std::runtime_error("not a lutex LUT file (no 'LUTEX-LUT' magic)");
  }
  if (line != kMagic && line != kMagicWithRig && line != kMagicWithForwardScatter) {
    throw std::runtime_error("unsupported LUT file version '" + line + "' (this lutex reads versions 1 to 3)");
  }
  if (!std::getline(stream, line)) throw std::runtime_error("truncated LUT file: no header");
  nlohmann::json header;
  try {
    header = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error("the LUT header is " + JsonErrorText(error));
  }
  FrustumLutGrid grid;
  long long num_values = -1;
  try {
    // Whole numbers in int's range (FrustumLutGrid::Check bounds them further), never cast from any number.
    const auto whole = [&header](const char* key) {
      return static_cast<int>(WholeNumber(header.at(key), std::string("the LUT header's ") + key, 0, INT_MAX));
    };
    grid.nx = whole("nx");
    grid.ny = whole("ny");
    grid.nz = whole("nz");
    grid.z_near = header.at("z_near").get<double>();
    grid.z_far = header.at("z_far").get<double>();
    const std::string spacing = header.at("depth_spacing").get<std::string>();
    if (spacing == "z") {
      grid.spacing = DepthSpacing::kUniformZ;
    } else if (spacing == "inverse_z") {
      grid.spacing = DepthSpacing::kUniformInverseZ;
    } else {
      throw std::runtime_error("unknown depth_spacing '" + spacing + "' (expected z or inverse_z)");
    }
    const std::string interpolation = header.at("alpha_interpolation").get<std::string>();
    if (interpolation == "trilinear") {
      grid.alpha_interpolation = AlphaInterpolation::kTrilinear;
    } else if (interpolation == "inverse_square") {
      grid.alpha_interpolation = AlphaInterpolation::kInverseSquare;
    } else {
      throw std::runtime_error("unknown alpha_interpolation '" + interpolation + "' (expected trilinear or inverse_square)");
    }
    grid.image_width = whole("image_width");
    if (header.contains("shading_light_in_cam")) {
      for (int c = 0; c < 3; ++c) grid.shading.light_in_cam[c] = header["shading_light_in_cam"].at(c).get<double>();
    }
    if (header.contains("shading_rig")) {
      for (const nlohmann::json& light : header["shading_rig"]) grid.shading.rig.lights.push_back(LightFromJson(light));
    }
    if (header.contains("forward_scatter")) {
      const nlohmann::json& scatter = header["forward_scatter"];
      for (int c = 0; c < 3; ++c) grid.forward_scatter.scattering[c] = scatter.at("scattering_per_m").at(c).get<double>();
      grid.forward_scatter.anisotropy_g = scatter.at("anisotropy_g").get<double>();
    }
    grid.image_height = whole("image_height");
    if (header.at("value_type").get<std::string>() != "float64 little-endian") {
      throw std::runtime_error("unsupported value_type");
    }
    if (header.contains("num_values")) {
      num_values = WholeNumber(header["num_values"], "the LUT header's num_values", 0, LLONG_MAX);
    }
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error("the LUT header lacks a field or has a wrong type: " + JsonErrorText(error));
  }
  try {
    grid.Check();
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(std::string("LUT header: ") + error.what());
  }
  const long long expected = static_cast<long long>(grid.NumNodes()) * 6;
  if (num_values != expected) {
    throw std::runtime_error("LUT header's num_values does not match its grid (" + std::to_string(expected) + ")");
  }
  // Before allocating the nodes: a header may promise up to 2^31 values that the file does not hold.
  if (const std::optional<std::uint64_t> left = BytesLeft(stream);
      left && *left < static_cast<std::uint64_t>(expected) * sizeof(double)) {
    throw std::runtime_error("truncated file: the LUT header promises " + std::to_string(expected) +
                             " values, the file holds " + std::to_string(*left / sizeof(double)));
  }
  FrustumLut lut(grid);
  for (int n = 0; n < grid.NumNodes(); ++n) {
    LutNode& node = lut.node(n);
    for (int c = 0; c < 3; ++c) node.alpha[c] = ReadBinary<double>(stream, "the LUT values");
    for (int c = 0; c < 3; ++c) node.beta[c] = ReadBinary<double>(stream, "the LUT values");
    if (!node.alpha.allFinite() || !node.beta.allFinite()) {
      throw std::runtime_error("LUT node " + std::to_string(n) + " has a value that is not finite");
    }
    // Calibration bounds both below by 0: a negative value is a corrupt file, and a negative alpha would
    // restore every pixel to a negative albedo.
    if ((node.alpha.array() < 0.0).any() || (node.beta.array() < 0.0).any()) {
      throw std::runtime_error("LUT node " + std::to_string(n) + " has a negative alpha or beta: the file is corrupt");
    }
  }
  if (stream.peek() != std::istream::traits_type::eof()) throw std::runtime_error("LUT file has data after its values");
  return lut;
}

FrustumLut ReadLut(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::binary, [](std::istream& s) { return ReadLut(s); });
}

void WriteLut(const FrustumLut& lut, std::ostream& stream) {
  const FrustumLutGrid& grid = lut.grid();
  nlohmann::json header;
  header["format"] = "lutex-lut";
  const bool with_rig = !grid.shading.rig.lights.empty();
  const bool with_forward_scatter = !grid.forward_scatter.IsNone();
  const char* magic = with_forward_scatter ? kMagicWithForwardScatter : with_rig ? kMagicWithRig : kMagic;
  header["version"] = with_forward_scatter ? 3 : with_rig ? 2 : 1;
  header["nx"] = grid.nx;
  header["ny"] = grid.ny;
  header["nz"] = grid.nz;
  header["z_near"] = grid.z_near;
  header["z_far"] = grid.z_far;
  header["depth_spacing"] = grid.spacing == DepthSpacing::kUniformZ ? "z" : "inverse_z";
  header["alpha_interpolation"] =
      grid.alpha_interpolation == AlphaInterpolation::kTrilinear ? "trilinear" : "inverse_square";
  header["image_width"] = grid.image_width;
  header["shading_light_in_cam"] = {grid.shading.light_in_cam.x(), grid.shading.light_in_cam.y(),
                                    grid.shading.light_in_cam.z()};
  if (with_rig) {
    header["shading_rig"] = nlohmann::json::array();
    for (const Light& light : grid.shading.rig.lights) header["shading_rig"].push_back(LightToJson(light));
  }
  if (with_forward_scatter) {
    const Eigen::Vector3d& b = grid.forward_scatter.scattering;
    header["forward_scatter"] = {{"scattering_per_m", {b.x(), b.y(), b.z()}},
                                 {"anisotropy_g", grid.forward_scatter.anisotropy_g}};
  }
  header["image_height"] = grid.image_height;
  header["node_layout"] = kLayout;
  header["value_type"] = "float64 little-endian";
  header["num_values"] = static_cast<long long>(grid.NumNodes()) * 6;
  stream << magic << "\n" << header.dump() << "\n";
  for (int n = 0; n < grid.NumNodes(); ++n) {
    const LutNode& node = lut.node(n);
    for (int c = 0; c < 3; ++c) WriteBinary<double>(stream, node.alpha[c]);
    for (int c = 0; c < 3; ++c) WriteBinary<double>(stream, node.beta[c]);
  }
}

void WriteLut(const FrustumLut& lut, const std::filesystem::path& path) {
  WriteFileAtomically(path, std::ios::binary, [&lut](std::ostream& s) { WriteLut(lut, s); });
}

}  // namespace lutex
