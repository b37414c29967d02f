#include "colmap_integration/io/colmap_array.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/workspace.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(ColmapArray, HeaderAndPlanarLayoutAreCOLMAPs) {
  cv::Mat normals(2, 3, CV_32FC3);
  for (int i = 0; i < 6; ++i) normals.at<cv::Vec3f>(i / 3, i % 3) = cv::Vec3f(float(i), float(10 + i), float(20 + i));
  std::stringstream stream;
  WriteColmapArray(normals, stream);
  const std::string bytes = stream.str();
  ASSERT_EQ(bytes.substr(0, 6), "3&2&3&");
  ASSERT_EQ(bytes.size(), 6 + 18 * sizeof(float));
  // Planar: all x components (0..5) first, then all y (10..15), then all z.
  float values[18];
  std::memcpy(values, bytes.data() + 6, sizeof(values));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(values[i], float(i));
    EXPECT_EQ(values[6 + i], float(10 + i));
    EXPECT_EQ(values[12 + i], float(20 + i));
  }
  const cv::Mat read = ReadColmapArray(stream);
  EXPECT_EQ(cv::norm(read, normals, cv::NORM_INF), 0.0);
}

TEST(ColmapArray, TruncatedAndGarbageFilesAreErrors) {
  testing::TempDir dir;
  cv::Mat depth(4, 5, CV_32F, cv::Scalar(1.5f));
  WriteColmapArray(depth, dir.path() / "d.bin");
  std::filesystem::resize_file(dir.path() / "d.bin", std::filesystem::file_size(dir.path() / "d.bin") - 4);
  try {
    ReadColmapArray(dir.path() / "d.bin");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos);
  }
  std::istringstream garbage("hello world");
  EXPECT_THROW(ReadColmapArray(garbage), std::runtime_error);
}

// Found reviewing the reader for fuzz/colmap_array_fuzzer: the header's size is checked against the file before
// the values are allocated, so a corrupt header cannot reserve up to 16 TiB.
TEST(ColmapArray, AHeaderPromisingMoreThanTheFileHoldsIsAnErrorBeforeAllocating) {
  std::istringstream huge(std::string("1048576&1048576&4&") + std::string(8, '\0'));
  try {
    ReadColmapArray(huge);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("promises 1048576x1048576x4 floats, the file has 2"), std::string::npos)
        << error.what();
  }
}

TEST(ColmapArray, NanBecomesColmapsZero) {
  cv::Mat depth(1, 2, CV_32F);
  depth.at<float>(0, 0) = std::nanf("");
  depth.at<float>(0, 1) = 2.0f;
  const cv::Mat zeroed = ReplaceNanWithZero(depth);
  EXPECT_EQ(zeroed.at<float>(0, 0), 0.0f);
  EXPECT_EQ(zeroed.at<float>(0, 1), 2.0f);
}

TEST(Workspace, FindsSparseModelAndRejectsFoldersWithout) {
  testing::TempDir dir;
  EXPECT_THROW(FindWorkspace(dir.path()), std::runtime_error);
  std::filesystem::create_directories(dir.path() / "sparse" / "0");
  std::ofstream(dir.path() / "sparse" / "0" / "cameras.txt") << "";
  const Workspace workspace = FindWorkspace(dir.path());
  EXPECT_EQ(workspace.sparse_dir, dir.path() / "sparse" / "0");
  EXPECT_EQ(workspace.OutputDir(), dir.path() / "lutex");
}

}  // namespace
}  // namespace lutex
