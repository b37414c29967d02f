// A failed write is put in the user's words, naming the file: a full disk as a full disk.

#include "lib/util/write_failure.h"

#include <unistd.h>

#include <cerrno>
#include <string>

#include <gtest/gtest.h>

#include "lib/util/file_streams.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(WriteFailure, NoSpaceIsAFullDiskNamingTheFile) {
  testing::TempDir dir;
  const std::string text = DescribeWriteFailure(dir.path() / "restored" / "a.png", ENOSPC, "writing failed");
  EXPECT_EQ(text.rfind((dir.path() / "restored" / "a.png").string() + ": the disk is full (", 0), 0u) << text;
  // The folder does not exist yet: the free space is that of the nearest folder that does.
  EXPECT_NE(text.find("free on the file system of " + (dir.path() / "restored").string()), std::string::npos) << text;
}

TEST(WriteFailure, OtherFailuresSayTheSystemsReason) {
  testing::TempDir dir;  // the test machine's temp folder has more than 1 MiB free
  EXPECT_EQ(DescribeWriteFailure(dir.path() / "a.png", EACCES, "x"),
            (dir.path() / "a.png").string() + ": cannot be written (Permission denied)");
  EXPECT_EQ(DescribeWriteFailure(dir.path() / "a.png", 0, "the mesh writer failed"),
            (dir.path() / "a.png").string() + ": cannot be written (the mesh writer failed)");
}

// Through the writer every file goes through: a file that cannot be created is named, and nothing is left.
TEST(WriteFailure, AnAtomicWriteThatCannotCreateItsFileNamesItAndLeavesNothing) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.path() / "read_only");
  std::filesystem::permissions(dir.path() / "read_only", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  try {
    WriteBytesAtomically(dir.path() / "read_only" / "a.bin", "abc", 3);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), (dir.path() / "read_only" / "a.bin").string() + ": cannot be written (Permission denied)");
  }
}

}  // namespace
}  // namespace lutex
