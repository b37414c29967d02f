// Options from the command line and from a --config file: the file's values apply, the command line wins,
// relative paths in the file are relative to its folder, and errors name the file and line.

#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "colmap_integration/cli/option_parser.h"
#include "lib/util/option_error.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

struct Parsed {
  fs::path targets;
  int nx = 40;
  double z_far = 5.0;
  bool correspondences = false;
  std::string blend = "fuse";
};

// Parses `arguments` (after "lutex run") into a fresh Parsed; `settings` receives group "stage".
Parsed Parse(std::vector<std::string> arguments, std::map<std::string, std::string>* settings = nullptr) {
  Parsed parsed;
  OptionParser parser("lutex test", "A test.");
  parser.AddPath("targets", &parsed.targets, "Targets.");
  parser.SetGroup("stage");
  parser.AddInt("lut-nx", &parsed.nx, "Cells.");
  parser.AddDouble("z-far", &parsed.z_far, "Far.");
  parser.AddFlag("correspondences", &parsed.correspondences, "Flag.");
  parser.AddString("blend", &parsed.blend, "Blend.");
  arguments.insert(arguments.begin(), {"lutex", "run"});
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  parser.Parse(static_cast<int>(argv.size()), argv.data(), 2);
  if (settings) *settings = parser.Settings("stage");
  return parsed;
}

TEST(OptionParserTest, ConfigFileValuesApplyAndTheCommandLineWins) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "dive");
  std::ofstream(dir.path() / "dive" / "lutex.conf") << "# the dive's options\n\n"
                                                     << "targets = calibration/targets.json\n"
                                                     << "  lut-nx = 20   \n"
                                                     << "--z-far=8\n"
                                                     << "correspondences\n"
                                                     << "blend = single\n";
  std::map<std::string, std::string> settings;
  const Parsed parsed =
      Parse({"--config", (dir.path() / "dive" / "lutex.conf").string(), "--lut-nx", "30"}, &settings);
  EXPECT_EQ(parsed.targets, dir.path() / "dive" / "calibration" / "targets.json");
  EXPECT_EQ(parsed.nx, 30);  // the command line wins
  EXPECT_DOUBLE_EQ(parsed.z_far, 8.0);
  EXPECT_TRUE(parsed.correspondences);
  EXPECT_EQ(parsed.blend, "single");
  const std::map<std::string, std::string> expected = {
      {"lut-nx", "30"}, {"z-far", "8"}, {"correspondences", "on"}, {"blend", "single"}};
  EXPECT_EQ(settings, expected);

  const Parsed negated = Parse({"--config", (dir.path() / "dive" / "lutex.conf").string(), "--no-correspondences"});
  EXPECT_FALSE(negated.correspondences);
}

TEST(OptionParserTest, ConfigFileErrorsNameTheFileAndLine) {
  testing::TempDir dir;
  const fs::path config = dir.path() / "bad.conf";
  std::ofstream(config) << "lut-nx = 20\nlut-nx = twenty\n";
  try {
    Parse({"--config", config.string()});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(config.string() + ":2: --lut-nx expects a whole number, not 'twenty'"),
              std::string::npos)
        << error.what();
  }
  std::ofstream(config) << "# the mesh comes later\ntargets =\n";
  try {
    Parse({"--config", config.string()});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), config.string() + ":2: --targets has an empty value");
  }
  EXPECT_THROW(Parse({"--targets="}), std::invalid_argument);
  EXPECT_THROW(Parse({"--targets", ""}), std::invalid_argument);
  std::ofstream(config) << "colour = red\n";
  EXPECT_THROW(Parse({"--config", config.string()}), std::invalid_argument);
  std::ofstream(config) << "z-far\n";
  EXPECT_THROW(Parse({"--config", config.string()}), std::invalid_argument);
  EXPECT_THROW(Parse({"--config", (dir.path() / "missing.conf").string()}), std::invalid_argument);
}

// Stages word errors with field names; the parser shows them as its flags.
TEST(OptionParserTest, OptionErrorsOfStagesAreWordedWithTheFlags) {
  Parsed parsed;
  OptionParser parser("lutex test", "A test.");
  parser.AddPath("targets-workspace", &parsed.targets, "Calibration images.");
  parser.AddInt("lut-nx", &parsed.nx, "Cells.");
  parser.AddDouble("z-far", &parsed.z_far, "Far.");
  parser.NameField("calibration.grid.nx", "lut-nx");
  EXPECT_EQ(parser.FlagOf("targets_workspace"), "--targets-workspace");
  EXPECT_EQ(parser.FlagOf("calibration.grid.z_far"), "--z-far");   // by its last component
  EXPECT_EQ(parser.FlagOf("calibration.grid.nx"), "--lut-nx");     // named
  EXPECT_EQ(parser.FlagOf("pure_water_stride"), "pure_water_stride");  // no such flag: the field itself
  try {
    parser.RunWithFlags([] { throw OptionError("{targets_workspace} needs {calibration.grid.nx} > 0"); });
    FAIL() << "no error";
  } catch (const OptionError&) {
    FAIL() << "the stage's error reached the user unworded";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "--targets-workspace needs --lut-nx > 0");
  }
}

}  // namespace
}  // namespace lutex
