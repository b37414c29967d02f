// The memory check: estimates add up their parts, and a stage whose estimate exceeds its limit is refused
// with the estimate, its parts and the limit in one message.

#include "lib/util/memory_budget.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace lutex {
namespace {

TEST(MemoryBudget, AnEstimateIsTheSumOfItsPartsAndSaysWhereTheMemoryGoes) {
  MemoryEstimate estimate;
  estimate.Add("2 workers' image buffers", 2.0 * 12e6, 72.0);  // two 12 MP images at 72 B a pixel
  estimate.Add("the mesh", 1e6, 100.0);
  EXPECT_DOUBLE_EQ(estimate.total_bytes(), 2.0 * 12e6 * 72.0 + 1e8);
  EXPECT_EQ(estimate.Describe(), "2 workers' image buffers 1.6 GiB, the mesh 95 MiB");
}

TEST(MemoryBudget, WhatExceedsTheLimitIsRefusedWithTheEstimateAndTheLimit) {
  MemoryEstimate estimate;
  estimate.Add("image buffers", 1.0, 3.0 * 1024 * 1024 * 1024);
  EXPECT_NO_THROW(CheckMemoryEstimate("restore", estimate, std::size_t{4} << 30));
  try {
    CheckMemoryEstimate("restore", estimate, std::size_t{2} << 30);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()),
              "restore needs about 3.0 GiB (image buffers 3.0 GiB), more than the memory limit of 2.0 GiB (the limit set)");
  }
}

TEST(MemoryBudget, WithoutALimitTheMachinesAvailableMemoryIsTheLimit) {
  const std::size_t available = AvailableMemoryBytes();
  ASSERT_GT(available, 0u) << "no MemAvailable in /proc/meminfo";
  // Other processes come and go between the two readings.
  EXPECT_NEAR(static_cast<double>(ResolveMemoryLimit(0)), static_cast<double>(available), 0.5 * static_cast<double>(available));
  EXPECT_EQ(ResolveMemoryLimit(12345), 12345u);
  MemoryEstimate too_much;
  too_much.Add("a 20000 x 20000 camera's ray table", 4e8, 12.0 * 1e3);  // far beyond any machine
  try {
    CheckMemoryEstimate("raycast", too_much, 0);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("(the machine's available memory)"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lutex
