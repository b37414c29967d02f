#include "lib/model/light_rig_json.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

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
