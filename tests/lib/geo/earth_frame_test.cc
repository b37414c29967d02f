#include "lib/geo/earth_frame.h"

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "tests/support/run_command.h"

namespace lutex {
namespace {

// ECEF of a point in `crs` by GDAL's gdaltransform (PROJ through another program): the ground truth.
Eigen::Vector3d EcefByGdal(const std::string& crs, const Eigen::Vector3d& point) {
  std::ostringstream command;
  command.precision(17);
  command << "echo '" << point.x() << " " << point.y() << " " << point.z() << "' | gdaltransform -s_srs " << crs
          << " -t_srs EPSG:4978";
  const testing::CommandResult result = testing::RunCommand(command.str());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  Eigen::Vector3d ecef = Eigen::Vector3d::Constant(NAN);
  std::istringstream(result.output) >> ecef.x() >> ecef.y() >> ecef.z();
  return ecef;
}

TEST(EarthFrame, GeodeticToEcefMatchesTheEllipsoidAndProj) {
  EXPECT_LT((EcefFromGeodetic({0, 0, 0}) - Eigen::Vector3d(6378137.0, 0, 0)).norm(), 1e-6);
  EXPECT_LT((EcefFromGeodetic({90, 0, 0}) - Eigen::Vector3d(0, 0, 6356752.314245)).norm(), 1e-3);  // semi-minor axis
  if (!testing::HaveProgram("gdaltransform")) GTEST_SKIP() << "gdaltransform (gdal-bin) is not installed";
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(54.32, 10.14, -5.0), Eigen::Vector3d(-33.9, 18.4, 120.0),
                                       Eigen::Vector3d(71.0, -170.0, -4000.0)}) {
    // EPSG:4979 takes latitude, longitude, height in that order through gdaltransform's axis mapping.
    const Eigen::Vector3d expected = EcefByGdal("EPSG:4979", Eigen::Vector3d(point.y(), point.x(), point.z()));
    EXPECT_LT((EcefFromGeodetic(point) - expected).norm(), 1e-3) << point.transpose();
  }
}

TEST(EarthFrame, AnEnuModelIsPlacedByTheTangentFrameAtItsOrigin) {
  Georeference georeference;
  georeference.frame = Georeference::Frame::kEnu;
  georeference.origin = {54.32, 10.14, -5.0};
  const MapFrame frame(georeference);
  const Eigen::Matrix4d ecef_from_model = EcefFromModelNear(frame, Eigen::Vector3d(30, -20, 1));
  const double latitude = 54.32 * M_PI / 180.0, longitude = 10.14 * M_PI / 180.0;
  const Eigen::Vector3d east(-std::sin(longitude), std::cos(longitude), 0.0);
  const Eigen::Vector3d up(std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
                           std::sin(latitude));
  const Eigen::Vector3d north = up.cross(east);
  EXPECT_LT((ecef_from_model.block<3, 1>(0, 0) - east).norm(), 1e-6);
  EXPECT_LT((ecef_from_model.block<3, 1>(0, 1) - north).norm(), 1e-6);
  EXPECT_LT((ecef_from_model.block<3, 1>(0, 2) - up).norm(), 1e-6);
  EXPECT_LT((ecef_from_model.topRightCorner<3, 1>() - EcefFromGeodetic(georeference.origin)).norm(), 1e-3);
}

TEST(EarthFrame, AUtmModelIsPlacedWithinMillimetresAcrossAHectare) {
  if (!testing::HaveProgram("gdaltransform")) GTEST_SKIP() << "gdaltransform (gdal-bin) is not installed";
  Georeference georeference;
  georeference.frame = Georeference::Frame::kProjected;
  georeference.crs = "EPSG:32632";
  georeference.origin = {500123.0, 6001234.0, -812.5};
  const MapFrame frame(georeference);
  const Eigen::Matrix4d ecef_from_model = EcefFromModelNear(frame, Eigen::Vector3d(50, 50, 0));
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(50, 50, 0), Eigen::Vector3d(0, 0, -3), Eigen::Vector3d(100, 100, 4),
                                       Eigen::Vector3d(0, 100, 0)}) {
    const Eigen::Vector3d expected = EcefByGdal("EPSG:32632", point + georeference.origin);
    EXPECT_LT(((ecef_from_model * point.homogeneous()).head<3>() - expected).norm(), 0.005) << point.transpose();
  }
}

}  // namespace
}  // namespace lutex
