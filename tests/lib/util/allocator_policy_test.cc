// The allocator policy (lib/util/allocator_policy.h), watched through glibc's own accounting: after it, a
// large block freed and allocated again is mapped from the system again and returned when freed. glibc's
// default would, after the first free, serve the same size from its heap and keep it there.

#include "lib/util/allocator_policy.h"

#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define LUTEX_FOREIGN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LUTEX_FOREIGN_ALLOCATOR 1
#endif
#endif

namespace lutex {
namespace {

TEST(AllocatorPolicy, ALargeBlockIsMappedFromTheSystemEachTimeAndReturned) {
#if !defined(__GLIBC__) || defined(LUTEX_FOREIGN_ALLOCATOR)
  GTEST_SKIP() << "glibc's own allocator only (this build replaces it)";
#else
  MapLargeBlocksFromTheSystem();
  const std::size_t size = 2 * kLargeBlockBytes;
  for (int round = 0; round < 3; ++round) {
    const std::size_t mapped_before = mallinfo2().hblkhd;
    void* block = std::malloc(size);
    ASSERT_NE(block, nullptr);
    std::memset(block, round, size);
    const std::size_t mapped_while_held = mallinfo2().hblkhd;
    std::free(block);
    EXPECT_GE(mapped_while_held, mapped_before + size) << "round " << round << ": the block came from a heap";
    EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "round " << round << ": the block was not returned";
  }
#endif
}

}  // namespace
}  // namespace lutex
