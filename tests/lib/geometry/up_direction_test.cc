#include "lib/geometry/up_direction.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"

namespace lutex {
namespace {

Eigen::Vector3d Tilted(const Eigen::Vector3d& direction, double degrees, const Eigen::Vector3d& about) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, about.normalized()) * direction;
}

TEST(UpDirection, ADownwardSurveyOfAnAlignedModelIsZUpExactly) {
  // A lawnmower survey looking down, each camera a few degrees off nadir (pitch and roll of the vehicle).
  std::vector<Eigen::Vector3d> directions;
  for (int i = 0; i < 12; ++i) {
    directions.push_back(Tilted(-Eigen::Vector3d::UnitZ(), 3.0 + (i % 3), Eigen::Vector3d(std::cos(i), std::sin(i), 0)));
  }
  EXPECT_EQ(UpFromViewingDirections(directions), Eigen::Vector3d::UnitZ());
}

TEST(UpDirection, AnUnalignedModelKeepsTheCamerasOwnUp) {
  // COLMAP's frame of a model never aligned: the survey looks along some direction 40 degrees off -y.
  const Eigen::Vector3d down = Tilted(-Eigen::Vector3d::UnitY(), 40.0, Eigen::Vector3d::UnitX());
  const std::vector<Eigen::Vector3d> directions = {down, down, Tilted(down, 2.0, Eigen::Vector3d::UnitZ())};
  const Eigen::Vector3d up = UpFromViewingDirections(directions);
  EXPECT_LT(std::acos(up.dot(-down)) * 180.0 / M_PI, 1.0);
  EXPECT_NEAR(up.norm(), 1.0, 1e-12);
}

TEST(UpDirection, CamerasLookingEveryWayCannotTellUp) {
  const std::vector<Eigen::Vector3d> directions = {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(),
                                                   Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  EXPECT_THROW(UpFromViewingDirections(directions), std::invalid_argument);
  EXPECT_THROW(UpFromViewingDirections({}), std::invalid_argument);
}

TEST(UpDirection, AxisNamesRoundTrip) {
  for (const char* name : {"x", "-x", "y", "-y", "z", "-z", "+z"}) {
    const auto axis = AxisFromName(name);
    ASSERT_TRUE(axis) << name;
    EXPECT_EQ(DirectionName(*axis), name[0] == '-' || name[0] == '+' ? std::string(name) : std::string("+") + name);
  }
  EXPECT_FALSE(AxisFromName("w"));
  EXPECT_FALSE(AxisFromName("zz"));
  EXPECT_FALSE(AxisFromName(""));
  EXPECT_EQ(DirectionName(Eigen::Vector3d(0.6, 0.0, 0.8)), "(0.600, 0.000, 0.800)");
}

TEST(UpDirection, FromTheCamerasOfAModel) {
  // Two images looking along -y of an unaligned model: up is +y.
  SparseModel model;
  for (std::uint32_t id = 1; id <= 2; ++id) {
    Image image;
    image.image_id = id;
    image.cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.5 * id, 3, 0), -Eigen::Vector3d::UnitY(),
                                                 Eigen::Vector3d::UnitZ());
    model.images[id] = image;
  }
  EXPECT_EQ(UpFromCameras(model), Eigen::Vector3d::UnitY());
  EXPECT_THROW(UpFromCameras(SparseModel()), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
