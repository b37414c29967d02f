#include "lib/image/picture_cache.h"

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace lutex {
namespace {

// A 100 x 100 8-bit picture (30,000 bytes) filled with `value`.
cv::Mat Picture(int value) { return cv::Mat(100, 100, CV_8UC3, cv::Scalar::all(value)); }

TEST(PictureCache, KeepsTheMostRecentlyUsedWithinItsBudget) {
  PictureCache cache(3 * 30000);
  int decodes = 0;
  const auto get = [&](std::size_t key) {
    return cache.Get(key, [&] {
      ++decodes;
      return Picture(static_cast<int>(key));
    });
  };
  for (std::size_t key : {1, 2, 3}) EXPECT_EQ(get(key).at<cv::Vec3b>(0, 0)[0], key);
  EXPECT_EQ(decodes, 3);
  EXPECT_EQ(cache.held_bytes(), 90000u);
  get(1);  // held: no decode, and now the most recent
  EXPECT_EQ(decodes, 3);
  get(4);  // drops 2, the least recently used
  EXPECT_EQ(decodes, 4);
  EXPECT_TRUE(cache.Holds(1));
  EXPECT_FALSE(cache.Holds(2));
  EXPECT_TRUE(cache.Holds(3));
  EXPECT_TRUE(cache.Holds(4));
  EXPECT_EQ(cache.held_bytes(), 90000u);
  EXPECT_EQ(get(2).at<cv::Vec3b>(0, 0)[0], 2);  // read again
  EXPECT_EQ(decodes, 5);
  EXPECT_EQ(cache.decodes(), 5u);
  EXPECT_FALSE(cache.Holds(3));
}

TEST(PictureCache, APictureLargerThanTheBudgetOrABudgetOfZeroHoldsNothing) {
  PictureCache small(29999);
  EXPECT_EQ(small.Get(1, [] { return Picture(7); }).at<cv::Vec3b>(0, 0)[0], 7);
  EXPECT_FALSE(small.Holds(1));
  EXPECT_EQ(small.held_bytes(), 0u);
  PictureCache none(0);
  none.Get(1, [] { return Picture(7); });
  EXPECT_FALSE(none.Holds(1));
}

TEST(PictureCache, AFailedDecodeKeepsNothingAndPassesTheError) {
  PictureCache cache(1 << 20);
  EXPECT_THROW(cache.Get(1, []() -> cv::Mat { throw std::runtime_error("a.png: truncated"); }), std::runtime_error);
  EXPECT_FALSE(cache.Holds(1));
  EXPECT_EQ(cache.Get(1, [] { return Picture(3); }).at<cv::Vec3b>(0, 0)[0], 3);
}

TEST(PictureCache, ThreadsGetTheRightPicturesAndTheBudgetHolds) {
  PictureCache cache(4 * 30000);
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 400; ++i) {
        const std::size_t key = static_cast<std::size_t>((i * 7 + t * 3) % 9);
        const cv::Mat picture = cache.Get(key, [key] { return Picture(static_cast<int>(key)); });
        if (picture.at<cv::Vec3b>(99, 99)[2] != key) ++wrong;
        if (cache.held_bytes() > 4 * 30000) ++wrong;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(wrong.load(), 0);
}

}  // namespace
}  // namespace lutex
