#include "lib/calibration/targets.h"

#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "lib/image/image_io.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

constexpr const char* kSquare = R"("corners_world": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])";

// The error of reading `text` as a targets file, or "" when it reads.
std::string ReadError(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  try {
    ReadTargets(path);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

// Both albedo encodings decode to linear (8-bit sRGB through the sRGB curve, fractions allowed); entries
// without corners are skipped.
TEST(Targets, ReadsLinearAndSrgbAlbedosAndSkipsEntriesWithoutCorners) {
  testing::TempDir dir;
  const auto path = dir.path() / "targets.json";
  std::ofstream(path) << R"({"targets": [{"name": "orange", "albedo_srgb8": [181, 110.5, 30], )" << kSquare
                      << R"(}, {"id": 7, "albedo_linear": [0.2, 0.3, 0.4], )" << kSquare
                      << R"(}, {"name": "sphere", "albedo_linear": [0.5, 0.5, 0.5]}]})";
  const std::vector<Target> targets = ReadTargets(path);
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_EQ(targets[0].name, "orange");
  EXPECT_NEAR(targets[0].albedo.x(), SrgbToLinear(181 / 255.0), 1e-12);
  EXPECT_NEAR(targets[0].albedo.y(), SrgbToLinear(110.5 / 255.0), 1e-12);
  EXPECT_EQ(targets[1].name, "7");
  EXPECT_DOUBLE_EQ(targets[1].albedo.z(), 0.4);
  EXPECT_EQ(targets[0].corners_world.size(), 4u);
}

// Each kind of bad entry is one error naming the file, the target and the problem.
TEST(Targets, BadEntriesAreErrorsNamingTheFileTheTargetAndTheProblem) {
  testing::TempDir dir;
  const auto path = dir.path() / "targets.json";
  const std::string file = path.string();
  const auto entry = [](const std::string& fields) { return R"({"targets": [{"name": "board", )" + fields + "}]}"; };
  EXPECT_EQ(ReadError(path, entry(std::string(R"("albedo_srgb8": [181, 256, 30], )") + kSquare)),
            file + ": target board: albedo_srgb8 must be in [0, 255]");
  EXPECT_EQ(ReadError(path, entry(std::string(R"("albedo_linear": [0.2, -0.1, 0.4], )") + kSquare)),
            file + ": target board: albedo_linear must be in [0, 1]");
  EXPECT_EQ(ReadError(path, entry(std::string(R"("albedo_linear": [0.2, 0.4], )") + kSquare)),
            file + ": target board: albedo_linear must have 3 values");
  EXPECT_EQ(ReadError(path, entry(kSquare)), file + ": target board: needs albedo_linear or albedo_srgb8");
  EXPECT_EQ(ReadError(path, entry(R"("albedo_linear": [0.2, 0.3, 0.4], "corners_world": [[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]])")),
            file + ": target board: corners_world are not coplanar (to 1 mm)");
  EXPECT_EQ(ReadError(path, entry(R"("albedo_linear": [0.2, 0.3, 0.4], "corners_world": [[0, 0, 0], [1, 0, 0], [2, 0, 0]])")),
            file + ": target board: corners_world must be at least 3 corners spanning an area");
  EXPECT_EQ(ReadError(path, R"({"targets": []})"), file + ": needs a non-empty \"targets\" array");
  EXPECT_NE(ReadError(path, R"({"targets": [)").find(file + ": not valid JSON"), std::string::npos);
  EXPECT_NE(ReadError(path, "").find(file + ": not valid JSON"), std::string::npos);
  try {
    ReadTargets(dir.path() / "absent.json");
    ADD_FAILURE() << "an absent file was read";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), (dir.path() / "absent.json").string() + ": no such targets file");
  }
}

// Found reviewing the reader for fuzz/targets_fuzzer: a name that is not a string escaped as the JSON library's
// own exception (a std::exception, not the std::runtime_error the reader promises).
TEST(Targets, OddEntriesAreClearErrorsNotTheJsonLibrarys) {
  testing::TempDir dir;
  const auto path = dir.path() / "targets.json";
  const std::string file = path.string();
  EXPECT_EQ(ReadError(path, R"({"targets": [{"name": 7, "albedo_linear": [0.2, 0.5], "corners_world": []}]})"),
            file + ": target target 0: albedo_linear must have 3 values");
  EXPECT_EQ(ReadError(path, R"({"targets": [3, "x"]})"), file + ": no planar target (with corners_world)");
}

}  // namespace
}  // namespace lutex
