#include "lib/calibration/observations.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

TEST(Observations, MergingKeepsOneIndexPerImagePath) {
  ObservationSet all;
  all.images = {"w/a.png", "w/b.png"};
  KnownColorObservation known;
  known.image = 1;
  all.known_colors.push_back(known);

  ObservationSet part;
  part.images = {"w/c.png", "w/b.png"};
  CorrespondenceObservation correspondence;
  correspondence.first.image = 0;   // c
  correspondence.second.image = 1;  // b
  part.correspondences.push_back(correspondence);
  PureWaterObservation water;
  water.image = 7;  // not in part.images
  part.pure_water.push_back(water);
  MergeObservations(part, &all);

  ASSERT_EQ(all.images.size(), 3u);
  EXPECT_EQ(all.images[2], "w/c.png");
  EXPECT_EQ(all.known_colors[0].image, 1);
  EXPECT_EQ(all.correspondences[0].first.image, 2);
  EXPECT_EQ(all.correspondences[0].second.image, 1);
  EXPECT_EQ(all.pure_water[0].image, -1);
}

}  // namespace
}  // namespace lutex
