#include "lib/model/light_rig_json.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(LightRigJson, ReadsEveryProfileWithItsParametersInSiUnits) {
  testing::TempDir dir;
  const std::filesystem::path path = dir.path() / "rig.json";
  std::ofstream(path) << R"({"lights": [
      {"name": "port", "position": [-0.4, 0, 0], "direction": [0, 0, 2], "power_W": 4, "profile": "cycles_spot",
       "spot_size_deg": 90, "spot_blend": 0.25},
      {"position": [0.4, 0.1, 0], "intensity": [1, 2, 3], "profile": "gaussian", "sigma_deg": 30}],
    "water": "ignored: a rig file may be a whole scene description"})";
  const LightRig rig = ReadLightRig(path);
  ASSERT_EQ(rig.lights.size(), 2u);
  const Light& port = rig.lights[0];
  EXPECT_EQ(port.name, "port");
  EXPECT_TRUE(port.position_in_cam.isApprox(Eigen::Vector3d(-0.4, 0, 0)));
  EXPECT_TRUE(port.direction_in_cam.isApprox(Eigen::Vector3d::UnitZ()));  // normalised
  EXPECT_NEAR(port.intensity.x(), 4.0 / (4.0 * M_PI), 1e-12);             // Cycles: I = P / (4 pi)
  EXPECT_EQ(port.profile, BeamProfile::kCyclesSpot);
  EXPECT_NEAR(port.spot_size_rad, M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(port.spot_blend, 0.25);
  const Light& starboard = rig.lights[1];
  EXPECT_EQ(starboard.name, "lights[1]");
  EXPECT_TRUE(starboard.intensity.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_EQ(starboard.profile, BeamProfile::kGaussian);
  EXPECT_NEAR(starboard.sigma_rad, M_PI / 6, 1e-12);
}

// What calibrate writes (water_prior.json) is what --shading-rig reads back, every profile with its
// parameters.
TEST(LightRigJson, AWrittenRigReadsBackAsItWas) {
  LightRig rig;
  for (BeamProfile profile : {BeamProfile::kIsotropic, BeamProfile::kCosinePower, BeamProfile::kGaussian,
                              BeamProfile::kCyclesSpot}) {
    Light light;
    light.name = BeamProfileName(profile);
    light.position_in_cam = Eigen::Vector3d(0.1 * static_cast<double>(rig.lights.size()), -0.2, 0.05);
    light.direction_in_cam = Eigen::Vector3d(0.1, 0, 1).normalized();
    light.intensity = Eigen::Vector3d(1, 2, 3);
    light.profile = profile;
    light.exponent = 3.0;
    light.sigma_rad = 0.4;
    light.spot_size_rad = 1.5;
    light.spot_blend = 0.3;
    rig.lights.push_back(light);
  }
  const LightRig back = ParseLightRig(nlohmann::json{{"lights", LightRigToJson(rig)}});
  ASSERT_EQ(back.lights.size(), rig.lights.size());
  for (std::size_t l = 0; l < rig.lights.size(); ++l) {
    const Light &a = rig.lights[l], &b = back.lights[l];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.profile, a.profile);
    EXPECT_TRUE(b.position_in_cam.isApprox(a.position_in_cam));
    EXPECT_TRUE(b.direction_in_cam.isApprox(a.direction_in_cam));
    EXPECT_TRUE(b.intensity.isApprox(a.intensity));
    for (double cos_psi : {1.0, 0.9, 0.7, 0.3}) EXPECT_NEAR(b.Profile(cos_psi), a.Profile(cos_psi), 1e-12) << l;
  }
}

TEST(LightRigJson, ErrorsNameTheFileAndTheKeyPath) {
  testing::TempDir dir;
  const auto error_of = [&](const std::string& text) {
    const std::filesystem::path path = dir.path() / "rig.json";
    std::ofstream(path) << text;
    try {
      ReadLightRig(path);
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string prefix = (dir.path() / "rig.json").string() + ": ";
  EXPECT_EQ(error_of(R"({"lights": []})"), prefix + "needs at least one light in lights[]");
  EXPECT_EQ(error_of(R"({"lights": [{"profile": "laser"}]})"),
            prefix + "lights[0].profile 'laser' is not isotropic, cosine_power, gaussian or cycles_spot");
  EXPECT_EQ(error_of(R"({"lights": [{"positon": [0, 0, 0]}]})"), prefix + "unknown key lights[0].positon");
  EXPECT_EQ(error_of(R"({"lights": [{"intensity": [1, -1, 1]}]})"), prefix + "lights[0].intensity must not be negative");
  EXPECT_EQ(error_of(R"({"lights": [{"position": [0, 0]}]})"), prefix + "lights[0].position must be an array of 3 numbers");
  const std::string missing = (dir.path() / "none.json").string();
  EXPECT_THROW(ReadLightRig(missing), std::runtime_error);
}

}  // namespace
}  // namespace lutex
