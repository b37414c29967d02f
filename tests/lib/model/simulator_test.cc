#include "lib/model/simulator.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/model/image_formation.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/raycast/forward_scatter_removal.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

// The plane z = 0 seen from `height` straight above (camera looking down, image down = world -y).
Mesh Floor() { return MakeHeightFieldMesh([](double, double) { return 0.0; }, -50, 50, -50, 50, 2, 2); }
Rigid3d Above(double height) {
  return CamFromWorldLookingAt(Eigen::Vector3d(0, 0, height), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
}

// In air, a point light at the camera, a fronto-parallel plane at distance d: a pixel whose ray meets the
// plane at P has radiance rho / pi * I * cos(i) / |P|^2 with cos(i) = d / |P|.
TEST(Simulator, InAirPointLightOnPlaneIsAnalytic) {
  const Mesh floor = Floor();
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d(0.8, 0.5, 0.2));
  const Simulator simulator(floor, PointLightAtCamera(2.0), Water::Air(), albedo);
  const Camera camera = Camera::Pinhole(1, 64, 48, 40, 40);
  const cv::Mat image = simulator.Render(CameraRays(camera), Above(1.5));
  for (int row = 0; row < 48; row += 5) {
    for (int col = 0; col < 64; col += 5) {
      const Eigen::Vector3d point = 1.5 * camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5));
      const double r = point.norm();
      const double expected_green = 0.5 / M_PI * 2.0 * (1.5 / r) / (r * r);
      EXPECT_NEAR(image.at<cv::Vec3f>(row, col)[1], expected_green, 1e-6 * expected_green);
      EXPECT_NEAR(image.at<cv::Vec3f>(row, col)[0] / image.at<cv::Vec3f>(row, col)[2], 0.8 / 0.2, 1e-5);
    }
  }
}

// The backscatter integral against an independent brute-force midpoint rule with 200,000 uniform steps
// written out here from the physics (two cosine-power lights, Henyey-Greenstein, clear water), and the
// default 96 log-spaced steps against 4096: both within 0.5 %.
TEST(Simulator, BackscatterConvergesToBruteForceIntegral) {
  const Mesh floor = Floor();
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.5));
  const Water water = testing::ClearWater();
  const LightRig rig = testing::TwoCosineLights(0.4, 1.2, 2.0);
  SimulatorOptions fine_options;
  fine_options.backscatter_steps = 4096;
  const Simulator coarse(floor, rig, water, albedo), fine(floor, rig, water, albedo, fine_options);
  for (const Eigen::Vector3d& ray : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.2, 1).normalized()}) {
    for (double range : {0.5, 2.0, 8.0}) {
      Eigen::Vector3d brute = Eigen::Vector3d::Zero();
      // The water starts 2 cm in front of the camera (SimulatorOptions::water_start).
      const int steps = 200000;
      const double ds = (range - 0.02) / steps;
      for (int k = 0; k < steps; ++k) {
        const double s = 0.02 + (k + 0.5) * ds;
        const Eigen::Vector3d point = s * ray;
        for (const Light& light : rig.lights) {
          const Eigen::Vector3d from_light = point - light.position_in_cam;
          const double d = from_light.norm();
          const double cos_psi = light.direction_in_cam.dot(from_light / d);
          if (cos_psi <= 0) continue;
          const double cos_scatter = (from_light / d).dot(-ray);
          const double g = water.anisotropy_g;
          const double phase = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cos_scatter, 1.5));
          for (int c = 0; c < 3; ++c) {
            const double cc = water.absorption[c] + water.scattering[c];
            brute[c] += water.scattering[c] * phase * light.intensity[c] * cos_psi * cos_psi / (d * d) *
                        std::exp(-cc * (d + s)) * ds;
          }
        }
      }
      const Eigen::Vector3d from_fine = fine.Backscatter(ray, range);
      const Eigen::Vector3d from_coarse = coarse.Backscatter(ray, range);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(from_fine[c], brute[c], 5e-3 * brute[c]) << "range " << range;
        EXPECT_NEAR(from_coarse[c], from_fine[c], 5e-3 * from_fine[c]) << "range " << range;
      }
    }
  }
}

// A box between the light and the floor casts a shadow: in air the shadowed floor is black, the lit floor
// is not. The light is 0.5 m to the side of the camera so the shadow is visible.
TEST(Simulator, ShadowsBlockDirectLight) {
  Mesh scene = Floor();
  AppendMesh(MakeBoxMesh(Eigen::Vector3d(0.45, -0.1, 1.0), Eigen::Vector3d(0.55, 0.1, 1.2)), &scene);
  LightRig rig;
  Light light;
  light.position_in_cam = Eigen::Vector3d(0.5, 0, 0);
  rig.lights.push_back(light);
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.5));
  const Simulator simulator(scene, rig, Water::Air(), albedo);
  const Camera camera = Camera::Pinhole(1, 101, 101, 50, 50);
  const Rigid3d cam_from_world = Above(2.0);
  const cv::Mat image = simulator.Render(CameraRays(camera), cam_from_world);
  // The floor point straight below the light, (0.5, 0, 0), is behind the box as seen from the light.
  const Eigen::Vector2d shadowed = camera.ImgFromCam(cam_from_world * Eigen::Vector3d(0.5, 0.0, 0.0));
  const Eigen::Vector2d lit = camera.ImgFromCam(cam_from_world * Eigen::Vector3d(-0.5, 0.0, 0.0));
  EXPECT_EQ(image.at<cv::Vec3f>(static_cast<int>(shadowed.y()), static_cast<int>(shadowed.x()))[1], 0.0f);
  EXPECT_GT(image.at<cv::Vec3f>(static_cast<int>(lit.y()), static_cast<int>(lit.x()))[1], 0.01f);
}

// With one point light at the camera the model's shading approximation is exact, so a render equals
// alpha cos_theta rho + beta with alpha and beta of the true LUT formula, pixel by pixel; on a tilted
// plane in water. The render reads backscatter from the per-camera table, which agrees with the direct
// integral to 0.3 % (see BackscatterTableMatchesDirectIntegration).
TEST(Simulator, RenderObeysTheImageFormationModelForALightAtTheCamera) {
  const Mesh plane = MakeHeightFieldMesh([](double x, double y) { return 0.3 * x - 0.1 * y; }, -30, 30, -30, 30, 2, 2);
  const Eigen::Vector3d rho(0.7, 0.4, 0.25);
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(rho);
  Light light;
  light.profile = BeamProfile::kGaussian;
  light.sigma_rad = 0.6;
  light.intensity = Eigen::Vector3d(3, 3, 3);
  LightRig rig;
  rig.lights.push_back(light);
  const Simulator simulator(plane, rig, testing::ClearWater(), albedo);
  const Camera camera = Camera::Pinhole(1, 32, 24, 20, 20);
  const Rigid3d cam_from_world = Above(2.0);
  const cv::Mat image = simulator.Render(CameraRays(camera), cam_from_world);
  const Eigen::Vector3d normal_in_cam =
      (cam_from_world.rotation * Eigen::Vector3d(-0.3, 0.1, 1.0)).normalized();
  for (int row = 0; row < 24; row += 3) {
    for (int col = 0; col < 32; col += 3) {
      const Eigen::Vector3d ray = camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5));
      // Planar depth of the plane along this ray (as in the ray-casting test).
      const Eigen::Vector3d plane_point = cam_from_world * Eigen::Vector3d(0, 0, 0);
      const double z = normal_in_cam.dot(plane_point) / normal_in_cam.dot(ray);
      const Eigen::Vector3d point = z * ray;
      const double cos_theta = std::abs(ShadingCosine(point, normal_in_cam));
      const Eigen::Vector3d expected = PredictIntensity(simulator.SignalFactor(point),
                                                        simulator.Backscatter(ray.normalized(), point.norm()),
                                                        cos_theta, rho);
      const cv::Vec3f actual = image.at<cv::Vec3f>(row, col);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 3e-3 * expected[c]);
    }
  }
}

// The per-camera table (256 log steps, a pixel grid every 8 px) against direct integration with 4096
// steps at arbitrary pixels and ranges: within 0.3 %.
TEST(Simulator, BackscatterTableMatchesDirectIntegration) {
  const Mesh floor = Floor();
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.5));
  SimulatorOptions fine_options;
  fine_options.backscatter_steps = 4096;
  const Simulator simulator(floor, testing::TwoCosineLights(0.4, 1.2, 2.0), testing::ClearWater(), albedo, fine_options);
  const Camera camera = Camera::Pinhole(1, 320, 240, 160, 160);
  const BackscatterTable table = simulator.MakeBackscatterTable(CameraRays(camera));
  for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(3.7, 5.2), Eigen::Vector2d(160.5, 120.5), Eigen::Vector2d(301.3, 77.9)}) {
    for (double range : {0.3, 1.1, 2.7, 9.0, 30.0}) {
      const Eigen::Vector3d direct = simulator.Backscatter(camera.CamFromImg(pixel).normalized(), range);
      const Eigen::Vector3d looked_up = table.Lookup(pixel.x(), pixel.y(), range);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(looked_up[c], direct[c], 3e-3 * direct[c]) << pixel.transpose() << " " << range;
    }
  }
}

TEST(Simulator, TrueLutNodesAreTheSignalFactorAndBackscatterAtTheNode) {
  const Mesh floor = Floor();
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.5));
  const Simulator simulator(floor, testing::TwoCosineLights(0.4, 1.2, 2.0), testing::ClearWater(), albedo);
  const Camera camera = Camera::Pinhole(1, 640, 480, 320, 320);
  FrustumLutGrid grid;
  grid.nx = 4;
  grid.ny = 3;
  grid.nz = 4;
  grid.z_near = 0.5;
  grid.z_far = 4.0;
  grid.image_width = 640;
  grid.image_height = 480;
  const FrustumLut lut = simulator.TrueLut(camera, grid);
  const Eigen::Vector3d ray = camera.CamFromImg(lut.NodePixel(1, 2));
  const Eigen::Vector3d point = grid.SlabDepth(3) * ray;
  EXPECT_LT((lut.node(1, 2, 3).alpha - simulator.SignalFactor(point)).norm(), 1e-12);
  EXPECT_LT((lut.node(1, 2, 3).beta - simulator.Backscatter(ray.normalized(), point.norm())).norm(), 1e-12);
  // Water eats red: alpha_red < alpha_blue far away; backscatter grows with depth along a ray.
  EXPECT_LT(lut.node(2, 1, 3).alpha[0], lut.node(2, 1, 3).alpha[2]);
  EXPECT_GT(lut.node(2, 1, 3).beta[2], lut.node(2, 1, 0).beta[2]);
}

// Face colours are linearised sRGB, constant over each face: the albedo pass of a two-colour floor.
TEST(Simulator, AlbedoFromFaceColours) {
  Mesh floor = Floor();
  for (std::size_t f = 0; f < floor.faces.size(); ++f) {
    floor.face_colors.emplace_back(f % 2 ? 255 : 128, 0, 0);
  }
  const Simulator simulator(floor, PointLightAtCamera(), Water::Air(), SurfaceAlbedo::FromFaceColors(floor));
  const cv::Mat albedo = simulator.RenderAlbedo(CameraRays(Camera::Pinhole(1, 40, 30, 20, 20)), Above(2.0));
  std::set<float> reds;
  for (int row = 0; row < 30; ++row) {
    for (int col = 0; col < 40; ++col) reds.insert(albedo.at<cv::Vec3f>(row, col)[0]);
  }
  EXPECT_EQ(reds.size(), 2u);
  EXPECT_NEAR(*reds.rbegin(), 1.0f, 1e-6f);
  EXPECT_NEAR(*reds.begin(), 0.2158605f, 1e-6f);  // sRGB 128 linearised
}

// A 2 x 2 texture on a floor whose UVs span it: texture row 0 is v = 1 (the +y side), nearest texels.
// Seen from above with image "down" = world -y, the top-left of the image is the (-x, +y) corner:
// texel (row 0, col 0).
TEST(Simulator, AlbedoFromTextureFollowsTheUvConvention) {
  const Mesh floor = MakeHeightFieldMesh([](double, double) { return 0.0; }, -1, 1, -1, 1, 4, 4);
  cv::Mat texture(2, 2, CV_32FC3);
  texture.at<cv::Vec3f>(0, 0) = cv::Vec3f(1, 0, 0);  // top-left: +y, -x
  texture.at<cv::Vec3f>(0, 1) = cv::Vec3f(0, 1, 0);
  texture.at<cv::Vec3f>(1, 0) = cv::Vec3f(0, 0, 1);
  texture.at<cv::Vec3f>(1, 1) = cv::Vec3f(1, 1, 1);
  const Simulator simulator(floor, PointLightAtCamera(), Water::Air(), SurfaceAlbedo::FromTexture(floor, texture));
  const cv::Mat albedo = simulator.RenderAlbedo(CameraRays(Camera::Pinhole(1, 40, 40, 40, 40)), Above(2.0));
  EXPECT_EQ(albedo.at<cv::Vec3f>(10, 10), cv::Vec3f(1, 0, 0));
  EXPECT_EQ(albedo.at<cv::Vec3f>(10, 30), cv::Vec3f(0, 1, 0));
  EXPECT_EQ(albedo.at<cv::Vec3f>(30, 10), cv::Vec3f(0, 0, 1));
  EXPECT_EQ(albedo.at<cv::Vec3f>(30, 30), cv::Vec3f(1, 1, 1));
}

TEST(Simulator, ResultsDoNotDependOnTheThreadCount) {
  const Mesh floor = MakeHeightFieldMesh([](double x, double y) { return 0.2 * std::sin(3 * x + y); }, -5, 5, -5, 5, 50, 50);
  const SurfaceAlbedo albedo = SurfaceAlbedo::Constant(Eigen::Vector3d::Constant(0.5));
  SimulatorOptions one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  const CameraRays rays(Camera::Pinhole(1, 40, 30, 25, 25));
  const cv::Mat a = Simulator(floor, testing::TwoCosineLights(0.4, 1.2, 2.0), testing::ClearWater(), albedo, one).Render(rays, Above(2));
  const cv::Mat b = Simulator(floor, testing::TwoCosineLights(0.4, 1.2, 2.0), testing::ClearWater(), albedo, two).Render(rays, Above(2));
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

// With forward scattering rendered, a patchy seafloor in coastal water seen from 2 m loses contrast (a
// dark patch is brightened by its bright neighbours). The simulator spreads the light from the surface,
// not the backscatter: taking the same scattering out of the render with its backscatter set aside, over
// the ray-cast ranges, gives the sharp render back.
TEST(Simulator, ForwardScatteringSpreadsTheLightFromTheSurfaceAsTheCorrectionAssumes) {
  SyntheticSeafloorOptions seafloor;
  seafloor.size_x = seafloor.size_y = 8.0;
  seafloor.cell_size = 0.04;
  const Mesh mesh = MakeSyntheticSeafloor(seafloor);
  const SurfaceAlbedo albedo = SurfaceAlbedo::FromVertexColors(mesh);
  Water coastal;
  coastal.absorption = Eigen::Vector3d(0.45, 0.12, 0.25);
  coastal.scattering = Eigen::Vector3d(0.35, 0.4, 0.38);
  coastal.anisotropy_g = 0.9;
  SimulatorOptions sharp, spread;
  spread.forward_scatter = true;
  const LightRig rig = testing::TwoCosineLights(0.4, 30.0, 2.0);
  const CameraRays rays(Camera::Pinhole(1, 200, 150, 120, 120));
  const Rigid3d cam_from_world = Above(2.0);
  const cv::Mat truth = Simulator(mesh, rig, coastal, albedo, sharp).Render(rays, cam_from_world);
  const cv::Mat scattered = Simulator(mesh, rig, coastal, albedo, spread).Render(rays, cam_from_world);
  const cv::Mat backscatter =
      Simulator(mesh, rig, coastal, SurfaceAlbedo::Constant(Eigen::Vector3d::Zero()), sharp).Render(rays, cam_from_world);
  const GeometryMaps maps = Simulator(mesh, rig, coastal, albedo, sharp).RenderGeometry(rays, cam_from_world, {});
  const cv::Mat corrected = WithoutForwardScatter(scattered, maps, rays, ForwardScatter::Of(coastal), 1e9, backscatter);
  const cv::Mat whole_image_corrected = WithoutForwardScatter(scattered, maps, rays, ForwardScatter::Of(coastal), 1e9);
  // The largest error relative to the pixel's true radiance.
  const auto worst_relative = [&](const cv::Mat& image) {
    double worst = 0.0;
    for (int row = 0; row < truth.rows; ++row) {
      for (int col = 0; col < truth.cols; ++col) {
        for (int c = 0; c < 3; ++c) {
          const double t = truth.at<cv::Vec3f>(row, col)[c];
          worst = std::max(worst, std::abs(image.at<cv::Vec3f>(row, col)[c] - t) / t);
        }
      }
    }
    return worst;
  };
  EXPECT_GT(worst_relative(scattered), 0.3);   // measured 0.39 at the 99th percentile, more at worst
  EXPECT_LT(worst_relative(corrected), 0.005);  // measured 0.0021
  // Taken out of the whole image, backscatter included, it sharpens the backscatter's gradients too.
  EXPECT_GT(worst_relative(whole_image_corrected), 0.05);  // measured 0.11
  // Air has no forward scattering: the option changes nothing there.
  const cv::Mat air = Simulator(mesh, rig, Water::Air(), albedo, spread).Render(rays, cam_from_world);
  EXPECT_EQ(cv::norm(air, Simulator(mesh, rig, Water::Air(), albedo, sharp).Render(rays, cam_from_world), cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace lutex
