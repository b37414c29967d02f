#include "lib/geo/map_frame.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/support/enu_to_utm.h"

namespace lutex {
namespace {

TEST(UtmZone, FollowsTheZonesAndTheirExceptions) {
  EXPECT_EQ(UtmCrsOf(54.32, 10.14), "EPSG:32632");
  EXPECT_EQ(UtmCrsOf(-33.9, 18.4), "EPSG:32734");
  EXPECT_EQ(UtmCrsOf(60.0, 5.0), "EPSG:32632");  // south-west Norway is 32V, not 31V
  EXPECT_EQ(UtmCrsOf(78.0, 15.0), "EPSG:32633");  // Svalbard
  EXPECT_EQ(UtmCrsOf(0.0, 179.9), "EPSG:32660");
  EXPECT_EQ(UtmCrsOf(0.0, -180.0), "EPSG:32601");
  EXPECT_EQ(UtmCrsOf(0.0, 181.0), "EPSG:32601");
}

TEST(MapFrame, AProjectedModelIsShiftedByItsOriginWithoutLoss) {
  Georeference georeference;
  georeference.frame = Georeference::Frame::kProjected;
  georeference.crs = "EPSG:32632";
  georeference.origin = {500123.0, 6001234.0, -812.5};
  const MapFrame frame(georeference);
  EXPECT_EQ(frame.crs(), "EPSG:32632");
  EXPECT_EQ(frame.crs_name(), "WGS 84 / UTM zone 32N");
  EXPECT_NE(frame.crs_wkt().find("UTM zone 32N"), std::string::npos);
  const Eigen::Vector3d in_model(1.2345, -6.789, 0.25);
  const Eigen::Vector3d in_map = frame.MapFromModel(in_model);
  EXPECT_NEAR(in_map.x(), 500124.2345, 1e-9);
  EXPECT_NEAR(in_map.y(), 6001227.211, 1e-9);
  EXPECT_NEAR(in_map.z(), -812.25, 1e-12);
  EXPECT_LT((frame.ModelFromMap(in_map) - in_model).norm(), 1e-9);
}

TEST(MapFrame, AnEnuModelLandsWhereTheClosedFormPutsItInItsUtmZone) {
  const double lat = 54.3201, lon = 10.1402, h = -25.0;
  Georeference georeference;
  georeference.frame = Georeference::Frame::kEnu;
  georeference.origin = {lat, lon, h};
  const MapFrame frame(georeference);
  ASSERT_EQ(frame.crs(), "EPSG:32632");
  std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {250.0, 0, 0}, {0, 400.0, -3.0}, {-700.0, -350.0, 12.5}};
  const std::vector<Eigen::Vector3d> in_model = points;
  frame.MapFromModel(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d expected = testing::ProjectedOfEnu(in_model[i], lat, lon, h, "EPSG:32632");
    EXPECT_NEAR(points[i].x(), expected.x(), 1e-3) << i;
    EXPECT_NEAR(points[i].y(), expected.y(), 1e-3) << i;
    // Heights are ellipsoidal: the tangent plane falls below the ellipsoid by d^2 / 2R away from the origin.
    const double d = in_model[i].head<2>().norm();
    EXPECT_NEAR(points[i].z(), h + in_model[i].z() + d * d / (2.0 * 6.38e6), 2e-3) << i;
  }
  // East is east: 250 m along the model's x is ~250 m of easting (grid convergence ~1.6 degrees here).
  EXPECT_NEAR((points[1] - points[0]).head<2>().norm(), 250.0 * 0.9997, 0.05);
  frame.ModelFromMap(points);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_LT((points[i] - in_model[i]).norm(), 1e-3) << i;
}

TEST(MapFrame, AnEnuModelCanBeMappedIntoAnotherCrs) {
  Georeference georeference;
  georeference.frame = Georeference::Frame::kEnu;
  georeference.origin = {54.3201, 10.1402, 0.0};
  georeference.crs = "EPSG:25832";  // ETRS89 / UTM 32N
  const MapFrame frame(georeference);
  EXPECT_EQ(frame.crs(), "EPSG:25832");
  const Eigen::Vector3d expected = testing::ProjectedOfEnu({10.0, 20.0, 0.0}, 54.3201, 10.1402, 0.0, "EPSG:32632");
  // ETRS89 and WGS 84 agree to within a metre here (PROJ's ballpark transformation is the identity).
  EXPECT_LT((frame.MapFromModel(Eigen::Vector3d(10.0, 20.0, 0.0)) - expected).head<2>().norm(), 1.0);
}

TEST(MapFrame, UnknownOrGeographicCrsAreClearErrors) {
  Georeference georeference;
  georeference.frame = Georeference::Frame::kProjected;
  georeference.crs = "EPSG:999999";
  try {
    MapFrame frame(georeference);
    FAIL() << "accepted an unknown CRS";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("EPSG:999999: the CRS is unknown to PROJ"), std::string::npos)
        << error.what();
  }
  georeference.crs = "EPSG:4326";
  try {
    MapFrame frame(georeference);
    FAIL() << "accepted a geographic CRS";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("not a projected CRS"), std::string::npos) << error.what();
  }
  Georeference enu;
  enu.frame = Georeference::Frame::kEnu;
  enu.origin = {95.0, 10.0, 0.0};
  EXPECT_THROW(MapFrame{enu}, std::invalid_argument);
}

TEST(MapFrame, WithoutAGeoreferenceTheModelIsTheMap) {
  const MapFrame frame(Georeference{});
  EXPECT_FALSE(frame.HasCrs());
  EXPECT_TRUE(frame.crs_wkt().empty());
  const Eigen::Vector3d point(3.0, -4.0, 0.5);
  EXPECT_EQ(frame.MapFromModel(point), point);
}

}  // namespace
}  // namespace lutex
