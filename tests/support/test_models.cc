#include "tests/support/test_models.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/test_cameras.h"

namespace lutex::testing {

SparseModel MakeTestModel(int num_models) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  SparseModel model;
  for (int id = 0; id < num_models; ++id) {
    const auto camera_id = static_cast<std::uint32_t>(id + 1);
    model.cameras[camera_id] = MakeCamera(static_cast<CameraModelId>(id), camera_id);
  }
  for (std::uint32_t image_id = 1; image_id <= 2u * static_cast<std::uint32_t>(num_models); ++image_id) {
    Image image;
    image.image_id = image_id;
    image.camera_id = 1 + (image_id - 1) % static_cast<std::uint32_t>(num_models);
    image.name = "dive_07/frame_" + std::to_string(1000 + image_id) + ".jpg";
    image.cam_from_world = Rigid3d(Eigen::Quaterniond(uniform(random), uniform(random), uniform(random),
                                                      uniform(random)).normalized(),
                                   Eigen::Vector3d(uniform(random), uniform(random), uniform(random)) * 10.0);
    for (int k = 0; k < 5; ++k) {
      Point2D point;
      point.xy = Eigen::Vector2d(320 + 300 * uniform(random), 240 + 200 * uniform(random));
      point.point3D_id = k < 3 ? static_cast<std::uint64_t>(k + 1) : kInvalidPoint3DId;
      image.points2D.push_back(point);
    }
    model.images[image_id] = image;
  }
  for (std::uint64_t point3D_id = 1; point3D_id <= 3; ++point3D_id) {
    Point3D point;
    point.point3D_id = point3D_id;
    point.xyz = Eigen::Vector3d(uniform(random), uniform(random), uniform(random)) * 5.0;
    point.color << static_cast<std::uint8_t>(10 * point3D_id), 255, 0;
    point.error = 0.25 * static_cast<double>(point3D_id);
    for (const auto& [image_id, image] : model.images) {
      point.track.push_back({image_id, static_cast<std::uint32_t>(point3D_id - 1)});
    }
    model.points3D[point3D_id] = point;
  }
  return model;
}

namespace {

template <typename Vector>
void ExpectNear(const Vector& expected, const Vector& actual, double tolerance, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (int i = 0; i < static_cast<int>(expected.size()); ++i) {
    EXPECT_LE(std::abs(expected[i] - actual[i]), tolerance * std::max(1.0, std::abs(expected[i])))
        << what << " [" << i << "]: " << expected[i] << " vs " << actual[i];
  }
}

}  // namespace

void ExpectModelsEqual(const SparseModel& expected, const SparseModel& actual, double tolerance) {
  ASSERT_EQ(expected.cameras.size(), actual.cameras.size());
  for (const auto& [id, camera] : expected.cameras) {
    const Camera& other = actual.cameras.at(id);
    EXPECT_EQ(camera.model_id, other.model_id) << "camera " << id;
    EXPECT_EQ(camera.width, other.width);
    EXPECT_EQ(camera.height, other.height);
    ExpectNear(camera.params, other.params, tolerance, "camera " + std::to_string(id));
  }
  ASSERT_EQ(expected.images.size(), actual.images.size());
  for (const auto& [id, image] : expected.images) {
    const Image& other = actual.images.at(id);
    EXPECT_EQ(image.camera_id, other.camera_id);
    EXPECT_EQ(image.name, other.name);
    ExpectNear(image.cam_from_world.rotation.coeffs(), other.cam_from_world.rotation.coeffs(), tolerance,
               "rotation of image " + std::to_string(id));
    ExpectNear(image.cam_from_world.translation, other.cam_from_world.translation, tolerance,
               "translation of image " + std::to_string(id));
    ASSERT_EQ(image.points2D.size(), other.points2D.size());
    for (std::size_t k = 0; k < image.points2D.size(); ++k) {
      ExpectNear(image.points2D[k].xy, other.points2D[k].xy, tolerance, "2-D point");
      EXPECT_EQ(image.points2D[k].point3D_id, other.points2D[k].point3D_id);
    }
  }
  ASSERT_EQ(expected.points3D.size(), actual.points3D.size());
  for (const auto& [id, point] : expected.points3D) {
    const Point3D& other = actual.points3D.at(id);
    ExpectNear(point.xyz, other.xyz, tolerance, "3-D point " + std::to_string(id));
    EXPECT_EQ(point.color, other.color);
    EXPECT_LE(std::abs(point.error - other.error), tolerance * std::max(1.0, point.error));
    ASSERT_EQ(point.track.size(), other.track.size());
    for (std::size_t k = 0; k < point.track.size(); ++k) {
      EXPECT_EQ(point.track[k].image_id, other.track[k].image_id);
      EXPECT_EQ(point.track[k].point2D_idx, other.track[k].point2D_idx);
    }
  }
}

}  // namespace lutex::testing
