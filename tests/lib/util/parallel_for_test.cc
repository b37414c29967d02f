#include "lib/util/parallel_for.h"

#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace lutex {
namespace {

TEST(ParallelFor, VisitsEveryItemExactlyOnce) {
  for (int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> visits(1000);
    ParallelFor(visits.size(), threads, [&](std::size_t i) { visits[i]++; });
    for (const auto& count : visits) ASSERT_EQ(count.load(), 1) << threads << " threads";
  }
}

TEST(ParallelFor, RethrowsTheFirstErrorAfterJoining) {
  EXPECT_THROW(ParallelFor(100, 4,
                           [](std::size_t i) {
                             if (i == 37) throw std::runtime_error("item 37 failed");
                           }),
               std::runtime_error);
}

TEST(ParallelFor, ResolvesThreadCounts) {
  EXPECT_EQ(ResolveNumThreads(3), 3);
  EXPECT_GE(ResolveNumThreads(0), 1);
  EXPECT_GE(ResolveNumThreads(-1), 1);
}

}  // namespace
}  // namespace lutex
