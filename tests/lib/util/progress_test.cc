#include "lib/util/progress.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

// 10 of 40 images in 5 s: 2 images/s, 30 left, so 15 s to go.
TEST(Progress, FormatsRateAndEta) {
  EXPECT_EQ(ProgressReporter::FormatStatus(10, 40, "images", 5.0), "10/40 images, 2.00 images/s, ETA 15 s");
}

TEST(Progress, FinalLineGivesTotalTime) {
  EXPECT_EQ(ProgressReporter::FormatStatus(40, 40, "images", 8.0), "40/40 images, 5.00 images/s, 8.0 s");
}

TEST(Progress, NothingDoneYetHasNoRate) {
  EXPECT_EQ(ProgressReporter::FormatStatus(0, 40, "images", 1.0), "0/40 images");
}

}  // namespace
}  // namespace lutex
