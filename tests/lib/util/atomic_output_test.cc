#include "lib/util/atomic_output.h"

#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "lib/util/file_streams.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream stream(path);
  return std::string(std::istreambuf_iterator<char>(stream), {});
}

TEST(AtomicOutput, CommittedFileReplacesTheOldOne) {
  testing::TempDir dir;
  const auto path = dir.path() / "sub" / "out.txt";
  WriteFileAtomically(path, std::ios::out, [](std::ostream& s) { s << "first"; });
  WriteFileAtomically(path, std::ios::out, [](std::ostream& s) { s << "second"; });
  EXPECT_EQ(ReadAll(path), "second");
}

// A writer that fails half-way leaves the previous file untouched and no temporary behind.
TEST(AtomicOutput, FailedWriteLeavesOldFileAndNoDebris) {
  testing::TempDir dir;
  const auto path = dir.path() / "out.txt";
  WriteFileAtomically(path, std::ios::out, [](std::ostream& s) { s << "good"; });
  EXPECT_THROW(WriteFileAtomically(path, std::ios::out,
                                   [](std::ostream& s) {
                                     s << "partial";
                                     throw std::runtime_error("disk on fire");
                                   }),
               std::runtime_error);
  EXPECT_EQ(ReadAll(path), "good");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(AtomicOutput, TemporaryKeepsTheExtension) {
  testing::TempDir dir;
  AtomicOutputFile output(dir.path() / "preview.png");
  EXPECT_EQ(output.temporary_path().extension(), ".png");
  EXPECT_THROW(output.Commit(), std::runtime_error);  // nothing written
}

}  // namespace
}  // namespace lutex
