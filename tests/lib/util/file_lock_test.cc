// One writer per workspace: a lock another process holds is refused naming the holder; the process that
// holds a lock may take it again (lutex run, then its stages), and only its outermost hold releases it.

#include "lib/util/file_lock.h"

#include <sys/wait.h>
#include <unistd.h>

#include <optional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

// Whether another process can take the lock at `path` now (it releases it at once).
bool AnotherProcessCanLock(const std::filesystem::path& path) {
  const pid_t child = fork();
  if (child == 0) {
    try {
      ExclusiveFileLock lock(path, "W");
      _exit(0);
    } catch (const std::runtime_error&) {
      _exit(1);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

TEST(FileLock, AHolderMayTakeItsLockAgainAndOnlyTheOutermostHoldReleasesIt) {
  testing::TempDir dir;
  const std::filesystem::path path = dir.path() / "W" / "lutex" / ".lock";
  std::optional<ExclusiveFileLock> outer(std::in_place, path, "W");
  EXPECT_FALSE(AnotherProcessCanLock(path));
  {
    const ExclusiveFileLock inner(dir.path() / "W" / "lutex" / ".." / "lutex" / ".lock", "W");  // another spelling
    EXPECT_FALSE(AnotherProcessCanLock(path));
  }
  EXPECT_FALSE(AnotherProcessCanLock(path)) << "the inner hold released the outer one";
  EXPECT_TRUE(std::filesystem::exists(path));
  outer.reset();
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "W" / "lutex")) << "the lock's own folder is removed with it";
  EXPECT_TRUE(AnotherProcessCanLock(path));
}

TEST(FileLock, AnotherProcesssLockIsRefusedNamingTheHolder) {
  testing::TempDir dir;
  const std::filesystem::path path = dir.path() / ".lock";
  const ExclusiveFileLock held(path, "W");
  const pid_t child = fork();
  if (child == 0) {
    try {
      ExclusiveFileLock lock(path, "W");
      _exit(2);
    } catch (const std::runtime_error& error) {
      const std::string expected = "W is in use by lutex pid " + std::to_string(getppid()) + " on ";
      _exit(std::string(error.what()).rfind(expected, 0) == 0 ? 0 : 1);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "2: taken although held; 1: the message does not name the holder";
}

}  // namespace
}  // namespace lutex
