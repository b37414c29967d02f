#include "lib/util/atomic_output.h"

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>

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

// The process id of a child that has exited and been reaped: no process has it (until reused).
pid_t DeadProcessId() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  return child;
}

// What a killed writer leaves (".NAME.tmpPID_N.EXT" of a dead process) is removed; a live writer's
// temporaries (this process's) and files that merely look alike are kept.
TEST(AtomicOutput, StaleTemporariesOfKilledWritersAreRemovedLiveOnesKept) {
  testing::TempDir dir;
  const std::string dead = std::to_string(DeadProcessId()), live = std::to_string(getpid());
  std::filesystem::create_directories(dir.path() / "restored" / "sub");
  const std::vector<std::string> stale = {"restored/.frame_0006.tmp" + dead + "_3.png",
                                          "restored/sub/.frame_0007.tmp" + dead + "_0.png"};
  const std::vector<std::string> kept = {"restored/.frame_0008.tmp" + live + "_1.png", "restored/.tmpnotes",
                                         "restored/.frame.tmpX_1.png", "restored/frame_0006.png"};
  for (const auto& names : {stale, kept}) {
    for (const std::string& name : names) std::ofstream(dir.path() / name) << "bytes";
  }
  EXPECT_TRUE(IsStaleTemporary(dir.path() / stale[0]));
  EXPECT_FALSE(IsStaleTemporary(dir.path() / kept[0]));
  EXPECT_EQ(RemoveStaleTemporaries(dir.path() / "restored"), 2u);
  for (const std::string& name : stale) EXPECT_FALSE(std::filesystem::exists(dir.path() / name)) << name;
  for (const std::string& name : kept) EXPECT_TRUE(std::filesystem::exists(dir.path() / name)) << name;
  EXPECT_EQ(RemoveStaleTemporaries(dir.path() / "missing"), 0u);

  // Of one file: only that file's, beside it.
  std::ofstream(dir.path() / (".lut.tmp" + dead + "_0.lut")) << "half a LUT";
  std::ofstream(dir.path() / (".other.tmp" + dead + "_0.lut")) << "another file's";
  EXPECT_EQ(RemoveStaleTemporariesOf(dir.path() / "lut.lut"), 1u);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / (".lut.tmp" + dead + "_0.lut")));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / (".other.tmp" + dead + "_0.lut")));

  // What a library adds to a temporary's name (GDAL's overview and the COG writer's staging file) is the
  // temporary's too.
  const std::vector<std::string> suffixed = {".ortho.tmp" + dead + "_0.tif.ovr.tmp", ".ortho.tmp" + dead + "_0.tif.staging.tif"};
  for (const std::string& name : suffixed) std::ofstream(dir.path() / name) << "part of a mosaic";
  std::ofstream(dir.path() / (".ortho.tmp" + live + "_0.tif.ovr.tmp")) << "a live writer's";
  EXPECT_EQ(RemoveStaleTemporariesOf(dir.path() / "ortho.tif"), 2u);
  for (const std::string& name : suffixed) EXPECT_FALSE(std::filesystem::exists(dir.path() / name)) << name;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / (".ortho.tmp" + live + "_0.tif.ovr.tmp")));
}

}  // namespace
}  // namespace lutex
