#include "lib/calibration/survey_correspondences.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

// A point seen by images `a` and `b`.
Point3D SeenBy(std::uint64_t id, std::uint32_t a, std::uint32_t b) {
  Point3D point;
  point.point3D_id = id;
  point.track = {{a, 0}, {b, 0}};
  return point;
}

TEST(CandidatePartners, SharedPointsFirstThenNearestLookAtPointsFillUp) {
  SparseModel model;
  // Images 1 and 2 share 5 points, 1 and 3 share 2; image 4 shares none (its features did not match).
  for (std::uint64_t id = 0; id < 5; ++id) model.points3D[id] = SeenBy(id, 1, 2);
  for (std::uint64_t id = 5; id < 7; ++id) model.points3D[id] = SeenBy(id, 1, 3);
  const std::map<std::uint32_t, Eigen::Vector3d> look_at = {
      {1, Eigen::Vector3d(0, 0, 0)}, {2, Eigen::Vector3d(1, 0, 0)}, {3, Eigen::Vector3d(2, 0, 0)},
      {4, Eigen::Vector3d(0.4, 0, 0)}};
  const auto candidates = CandidatePartners(model, look_at, 3);
  EXPECT_EQ(candidates.at(1), (std::vector<std::uint32_t>{2, 3, 4}));  // by shared points, then nearest
  EXPECT_EQ(candidates.at(3), (std::vector<std::uint32_t>{1, 2, 4}));  // 1 shares; 2 is nearer than 4
  // Image 4 shares nothing but still gets partners: the images looking at the nearest points.
  EXPECT_EQ(candidates.at(4), (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(CandidatePartners(model, look_at, 1).at(2), (std::vector<std::uint32_t>{1}));
}

TEST(CandidatePartners, ImagesWithoutSamplesAreNeitherAskedNorAsking) {
  SparseModel model;
  model.points3D[0] = SeenBy(0, 1, 2);
  const std::map<std::uint32_t, Eigen::Vector3d> look_at = {{1, Eigen::Vector3d::Zero()}};
  const auto candidates = CandidatePartners(model, look_at, 4);
  EXPECT_TRUE(candidates.count(2) == 0);
  EXPECT_TRUE(candidates.count(1) == 0 || candidates.at(1).empty());
}

}  // namespace
}  // namespace lutex
