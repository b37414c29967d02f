#include "lib/geometry/camera.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/support/test_cameras.h"

namespace lutex {
namespace {

using testing::MakeCamera;

class EveryCameraModel : public ::testing::TestWithParam<int> {};

// Every pixel of a 33x25 grid over the whole image (borders included) unprojects to a ray that projects
// back to the same pixel to 1e-9 px.
TEST_P(EveryCameraModel, PixelRoundTripOverTheImage) {
  const Camera camera = MakeCamera(static_cast<CameraModelId>(GetParam()));
  camera.Check("test");
  double worst = 0.0;
  for (int i = 0; i <= 32; ++i) {
    for (int j = 0; j <= 24; ++j) {
      const Eigen::Vector2d pixel(0.5 + i * 639.0 / 32.0, 0.5 + j * 479.0 / 24.0);
      const Eigen::Vector3d ray = camera.CamFromImg(pixel);
      ASSERT_TRUE(ray.allFinite()) << pixel.transpose();
      EXPECT_DOUBLE_EQ(ray.z(), 1.0);
      worst = std::max(worst, (camera.ImgFromCam(2.5 * ray) - pixel).norm());
    }
  }
  EXPECT_LT(worst, 1e-9) << CameraModelName(camera.model_id);
}

// A point in front of the camera projects into the image and unprojects to its own ray: the normalised
// coordinates agree to 1e-9.
TEST_P(EveryCameraModel, PointRoundTrip) {
  const Camera camera = MakeCamera(static_cast<CameraModelId>(GetParam()));
  for (double a = -0.5; a <= 0.5; a += 0.125) {
    for (double b = -0.4; b <= 0.4; b += 0.1) {
      const Eigen::Vector3d point_in_cam(3.0 * a, 3.0 * b, 3.0);
      const Eigen::Vector3d ray = camera.CamFromImg(camera.ImgFromCam(point_in_cam));
      EXPECT_NEAR(ray.x(), a, 1e-9) << CameraModelName(camera.model_id);
      EXPECT_NEAR(ray.y(), b, 1e-9) << CameraModelName(camera.model_id);
    }
  }
}

// The ray through the principal point is the optical axis for every model.
TEST_P(EveryCameraModel, PrincipalPointIsOpticalAxis) {
  const Camera camera = MakeCamera(static_cast<CameraModelId>(GetParam()));
  const Eigen::Vector2d centre = camera.ImgFromCam(Eigen::Vector3d(0, 0, 7));
  EXPECT_NEAR(centre.x(), camera.PrincipalPointX(), 1e-12);
  EXPECT_NEAR(centre.y(), camera.PrincipalPointY(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllModels, EveryCameraModel, ::testing::Range(0, kNumCameraModels),
                         [](const ::testing::TestParamInfo<int>& param_info) {
                           return CameraModelName(static_cast<CameraModelId>(param_info.param));
                         });

// Pinhole projection by hand: x = fx * X / Z + cx.
TEST(Camera, PinholeMatchesHandComputation) {
  const Camera camera = MakeCamera(CameraModelId::kPinhole);
  const Eigen::Vector2d pixel = camera.ImgFromCam(Eigen::Vector3d(1.0, -0.5, 4.0));
  EXPECT_DOUBLE_EQ(pixel.x(), 500.0 * 0.25 + 322.0);
  EXPECT_DOUBLE_EQ(pixel.y(), 520.0 * -0.125 + 238.0);
}

// OPENCV radial term by hand at a point off-axis: u_d = u (1 + k1 r^2 + k2 r^4) + 2 p1 u v + p2 (r^2 + 2u^2).
TEST(Camera, OpenCVMatchesHandComputation) {
  const Camera camera = MakeCamera(CameraModelId::kOpenCV);
  const double u = 0.3, v = -0.2, r2 = u * u + v * v;
  const double k1 = -0.1, k2 = 0.02, p1 = 0.001, p2 = -0.0015;
  const double ud = u * (1 + k1 * r2 + k2 * r2 * r2) + 2 * p1 * u * v + p2 * (r2 + 2 * u * u);
  const double vd = v * (1 + k1 * r2 + k2 * r2 * r2) + 2 * p2 * u * v + p1 * (r2 + 2 * v * v);
  const Eigen::Vector2d pixel = camera.ImgFromCam(Eigen::Vector3d(u, v, 1.0));
  EXPECT_NEAR(pixel.x(), 500 * ud + 322, 1e-12);
  EXPECT_NEAR(pixel.y(), 520 * vd + 238, 1e-12);
}

// Equidistant fisheye without distortion: the image radius is f * theta.
TEST(Camera, FisheyeIsEquidistant) {
  Camera camera = MakeCamera(CameraModelId::kOpenCVFisheye);
  camera.params = {300, 300, 320, 240, 0, 0, 0, 0};
  const double theta = 1.2;  // 69 degrees off-axis
  const Eigen::Vector2d pixel = camera.ImgFromCam(Eigen::Vector3d(std::tan(theta), 0, 1));
  EXPECT_NEAR(pixel.x() - 320, 300 * theta, 1e-9);
}

TEST(Camera, PointsBehindTheCameraDoNotProject) {
  const Camera camera = MakeCamera(CameraModelId::kPinhole);
  EXPECT_FALSE(camera.ImgFromCam(Eigen::Vector3d(0, 0, -1)).allFinite());
}

TEST(Camera, ModelNamesAndIdsAgreeWithColmap) {
  EXPECT_EQ(CameraModelName(CameraModelId::kOpenCV), "OPENCV");
  EXPECT_EQ(CameraModelIdFromName("THIN_PRISM_FISHEYE"), CameraModelId::kThinPrismFisheye);
  EXPECT_EQ(static_cast<int>(CameraModelIdFromName("RAD_TAN_THIN_PRISM_FISHEYE")), 11);
  EXPECT_EQ(CameraModelNumParams(CameraModelId::kFullOpenCV), 12u);
  EXPECT_EQ(CameraModelNumParams(CameraModelId::kRadTanThinPrismFisheye), 16u);
}

TEST(Camera, UnknownModelsAreNamedInTheError) {
  try {
    CameraModelIdFromInt(42);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("42"), std::string::npos);
  }
  EXPECT_THROW(CameraModelIdFromName("PANORAMIC"), std::invalid_argument);
}

TEST(Camera, CheckRejectsWrongParameterCountAndNonsense) {
  Camera camera = MakeCamera(CameraModelId::kOpenCV);
  camera.params.pop_back();
  EXPECT_THROW(camera.Check("cameras.txt"), std::runtime_error);
  camera = MakeCamera(CameraModelId::kPinhole);
  camera.params[0] = std::nan("");
  EXPECT_THROW(camera.Check("cameras.txt"), std::runtime_error);
  camera = MakeCamera(CameraModelId::kPinhole);
  camera.params[1] = -5;
  EXPECT_THROW(camera.Check("cameras.txt"), std::runtime_error);
  camera = MakeCamera(CameraModelId::kPinhole);
  camera.width = 0;
  EXPECT_THROW(camera.Check("cameras.txt"), std::runtime_error);
}

}  // namespace
}  // namespace lutex
