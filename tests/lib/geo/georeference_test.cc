#include "lib/geo/georeference.h"

#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(Georeference, AWrittenFileReadsBackAsItWas) {
  testing::TempDir dir;
  Georeference georeference;
  georeference.frame = Georeference::Frame::kProjected;
  georeference.crs = "EPSG:32632";
  georeference.origin = {500123.456789, 6001234.987654, -812.5};
  WriteGeoreference(georeference, dir.path() / "georef.json");
  const Georeference read = ReadGeoreference(dir.path() / "georef.json");
  EXPECT_EQ(read.frame, georeference.frame);
  EXPECT_EQ(read.crs, georeference.crs);
  EXPECT_EQ(read.origin, georeference.origin);  // doubles, exactly
}

TEST(Georeference, BadFilesNameTheFileAndTheProblem) {
  testing::TempDir dir;
  const auto read = [&](const std::string& text) {
    std::ofstream(dir.path() / "georef.json") << text;
    try {
      ReadGeoreference(dir.path() / "georef.json");
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  const std::string path = (dir.path() / "georef.json").string();
  EXPECT_EQ(read(R"({"frame": "utm", "origin": [0, 0, 0]})"), path + ": frame must be \"projected\" or \"enu\", not \"utm\"");
  EXPECT_NE(read(R"({"frame": "enu"})").find("origin is required"), std::string::npos);
  EXPECT_NE(read(R"({"frame": "enu", "origin": [95, 0, 0]})").find("latitude"), std::string::npos);
  EXPECT_NE(read(R"({"frame": "projected", "origin": [0, 0, 0]})").find("needs a CRS"), std::string::npos);
  EXPECT_NE(read(R"({"frame": "enu", "origin": [0, 0, 0], "orign": 1})").find("orign"), std::string::npos);
  EXPECT_NE(read(R"({"frame": "enu", "origin": [0, 0})").find(path), std::string::npos);
  EXPECT_THROW(ReadGeoreference(dir.path() / "missing.json"), std::runtime_error);
}

TEST(Georeference, TriplesAreThreeFiniteNumbers) {
  EXPECT_EQ(ParseTriple("500123.5,6001234, -812.5", "o"), Eigen::Vector3d(500123.5, 6001234, -812.5));
  EXPECT_THROW(ParseTriple("1,2", "o"), std::invalid_argument);
  EXPECT_THROW(ParseTriple("1,2,3,4", "o"), std::invalid_argument);
  EXPECT_THROW(ParseTriple("1,nan,3", "o"), std::invalid_argument);
  EXPECT_THROW(ParseTriple("1;2;3", "o"), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
