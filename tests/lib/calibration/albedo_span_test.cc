// The known colours' albedo span per channel, and the warning for a channel they span too narrowly: the
// Blender boards (sRGB8 [181, 110, 30] and [80, 160, 90]) leave blue at 0.013 to 0.10; a chessboard's
// black and white span every channel; in air one bright card does.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/albedo_span.h"

namespace lutex {
namespace {

std::vector<KnownColorObservation> OfAlbedos(const std::vector<Eigen::Vector3d>& albedos) {
  std::vector<KnownColorObservation> observations;
  for (const Eigen::Vector3d& albedo : albedos) {
    KnownColorObservation observation;
    observation.albedo = albedo;
    observations.push_back(observation);
  }
  return observations;
}

TEST(AlbedoSpan, TheBlenderBoardsLeaveBlueNarrowAndSayWhatWouldFixIt) {
  const AlbedoSpan span =
      SpanOfKnownColours(OfAlbedos({Eigen::Vector3d(0.462, 0.155, 0.0130), Eigen::Vector3d(0.080, 0.351, 0.103)}));
  EXPECT_EQ(span.count, 2u);
  EXPECT_NEAR(span.lowest.z(), 0.0130, 1e-12);
  EXPECT_NEAR(span.highest.z(), 0.103, 1e-12);
  const std::vector<std::string> warnings = NarrowSpanWarnings(span, false, false, false);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("blue: the targets span albedo 0.013 to 0.103 only", 0), 0u) << warnings[0];
  EXPECT_NE(warnings[0].find("extrapolated"), std::string::npos);
  EXPECT_NE(warnings[0].find("--pure-water"), std::string::npos);
  EXPECT_NE(warnings[0].find("--correspondences"), std::string::npos);
  // What the calibration already has is not suggested again.
  const std::vector<std::string> with_both = NarrowSpanWarnings(span, false, true, true);
  ASSERT_EQ(with_both.size(), 1u);
  EXPECT_EQ(with_both[0].find("--pure-water"), std::string::npos);
  EXPECT_EQ(with_both[0].find("--correspondences"), std::string::npos);
}

TEST(AlbedoSpan, AChessboardSpansEveryChannelAndOneGreyCardSpansNone) {
  EXPECT_TRUE(NarrowSpanWarnings(SpanOfKnownColours(OfAlbedos({Eigen::Vector3d::Constant(0.04),
                                                                Eigen::Vector3d::Constant(0.8)})),
                                 false, false, false)
                  .empty());
  const std::vector<std::string> grey =
      NarrowSpanWarnings(SpanOfKnownColours(OfAlbedos({Eigen::Vector3d::Constant(0.5)})), false, true, false);
  ASSERT_EQ(grey.size(), 3u);  // bright, but one albedo: alpha and backscatter cannot be told apart
  EXPECT_NE(grey[0].find("hard to tell apart"), std::string::npos);
  // In air there is no backscatter: one bright card is enough.
  EXPECT_TRUE(NarrowSpanWarnings(SpanOfKnownColours(OfAlbedos({Eigen::Vector3d::Constant(0.5)})), true, false, false)
                  .empty());
  EXPECT_TRUE(NarrowSpanWarnings(SpanOfKnownColours({}), false, false, false).empty());
}

}  // namespace
}  // namespace lutex
