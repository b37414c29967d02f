// Run on the allocator `lutex` is linked with (tests/CMakeLists.txt links this binary as `lutex` is).

#include <cstddef>
#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "lib/util/memory_budget.h"

extern "C" int MallocExtension_GetNumericProperty(const char* property, std::size_t* value) __attribute__((weak));

namespace lutex {
namespace {

TEST(AllocatorFreeBytes, CountsWhatTheAllocatorKeepsAfterAStageFreesIt) {
  if (MallocExtension_GetNumericProperty == nullptr) {
    EXPECT_EQ(AllocatorFreeBytes(), 0u);
    GTEST_SKIP() << "built with the system's malloc (LUTEX_MALLOC=system or a sanitizer build), which keeps no "
                    "large free blocks: AllocatorFreeBytes is 0";
  }
  constexpr std::size_t kBytes = std::size_t{128} << 20;
  const std::size_t before = AllocatorFreeBytes();
  {
    std::unique_ptr<char[]> block(new char[kBytes]);
    std::memset(block.get(), 1, kBytes);
  }
  // tcmalloc keeps most of a freed block for the next allocation, and the budget counts it as available.
  const std::size_t after = AllocatorFreeBytes();
  EXPECT_GT(static_cast<double>(after) - static_cast<double>(before), 0.5 * kBytes);
  // Taken again, it is no longer free.
  std::unique_ptr<char[]> again(new char[kBytes]);
  std::memset(again.get(), 2, kBytes);
  EXPECT_LT(static_cast<double>(AllocatorFreeBytes()), static_cast<double>(after) - 0.5 * kBytes);
}

}  // namespace
}  // namespace lutex
