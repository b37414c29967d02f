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

// Each worker index is in range and runs on one thread at a time: per-worker scratch needs no lock.
TEST(ParallelFor, WorkerIndicesAreInRangeAndNeverShared) {
  for (int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> busy(static_cast<std::size_t>(threads));
    std::atomic<int> overlaps{0}, out_of_range{0};
    ParallelForOnWorkers(500, threads, [&](std::size_t, int worker) {
      if (worker < 0 || worker >= threads) {
        ++out_of_range;
        return;
      }
      if (busy[static_cast<std::size_t>(worker)]++ != 0) ++overlaps;
      volatile double sink = 0.0;
      for (int k = 0; k < 2000; ++k) sink = sink + k;
      busy[static_cast<std::size_t>(worker)]--;
    });
    EXPECT_EQ(out_of_range.load(), 0) << threads << " threads";
    EXPECT_EQ(overlaps.load(), 0) << threads << " threads";
  }
}

TEST(ParallelFor, ResolvesThreadCounts) {
  EXPECT_EQ(ResolveNumThreads(3), 3);
  EXPECT_GE(ResolveNumThreads(0), 1);
  EXPECT_GE(ResolveNumThreads(-1), 1);
}

}  // namespace
}  // namespace lutex
