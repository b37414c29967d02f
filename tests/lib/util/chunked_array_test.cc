#include "lib/util/chunked_array.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include <gtest/gtest.h>

namespace lutex {
namespace {

struct Texel {
  std::array<float, 20> values{};  // 80 bytes: 8192 of them in a block of 1 MiB
  std::uint8_t count = 0;
};

TEST(ChunkedArray, HoldsEveryElementOnceInBlocksOfAtMostAMebibyte) {
  constexpr std::size_t kSize = 3 * 8192 + 5;  // three full blocks and part of a fourth
  ChunkedArray<Texel> array(kSize);
  ASSERT_EQ(array.size(), kSize);
  EXPECT_EQ(array.num_chunks(), 4u);  // 8192 a block: the most elements, a power of two, in 1 MiB
  for (std::size_t i = 0; i < kSize; ++i) {
    EXPECT_EQ(array[i].count, 0) << i;  // value-initialised
    EXPECT_EQ(array[i].values[19], 0.0f) << i;
    array[i].values[0] = static_cast<float>(i);
  }
  // No two indices share an element: each keeps what was written to it, across the blocks' borders.
  for (std::size_t i = 0; i < kSize; ++i) ASSERT_EQ(array[i].values[0], static_cast<float>(i)) << i;
  const ChunkedArray<Texel>& read = array;
  EXPECT_EQ(read[8191].values[0], 8191.0f);
  EXPECT_EQ(read[8192].values[0], 8192.0f);
}

TEST(ChunkedArray, AnEmptyArrayHasNoBlocksAndAnElementLargerThanABlockHasOneEach) {
  EXPECT_EQ(ChunkedArray<Texel>(0).num_chunks(), 0u);
  struct Large {
    std::array<char, (std::size_t{3} << 20)> bytes;
  };
  ChunkedArray<Large> large(3);
  EXPECT_EQ(large.num_chunks(), 3u);
  large[2].bytes[0] = 7;
  EXPECT_EQ(large[2].bytes[0], 7);
  EXPECT_EQ(large[1].bytes[0], 0);
}

}  // namespace
}  // namespace lutex
