#include "lib/raycast/raycast_scene.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"

namespace lutex {
namespace {

// The plane through `point` with unit `normal`, as a 200 m square of two triangles.
Mesh PlaneMesh(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d u = normal.unitOrthogonal() * 100.0;
  const Eigen::Vector3d v = normal.cross(u);
  Mesh mesh;
  mesh.vertices = {point - u - v, point + u - v, point + u + v, point - u + v};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

Camera DistortedCamera() {
  Camera camera;
  camera.camera_id = 1;
  camera.model_id = CameraModelId::kOpenCV;
  camera.width = 160;
  camera.height = 120;
  camera.params = {100, 102, 81, 59, -0.12, 0.02, 0.001, -0.001};
  return camera;
}

// Rolling terrain with a boulder on it, and a view from above that sees both.
Mesh TerrainWithBoulder() {
  Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.2 * std::sin(3 * x) * std::cos(2 * y); },
                                  -3, 3, -3, 3, 60, 60);
  AppendMesh(MakeSphereMesh(Eigen::Vector3d(0.3, 0.2, 0.3), 0.4, 24, 48), &mesh);
  return mesh;
}

Rigid3d LookingDownAtTheTerrain() {
  return CamFromWorldLookingAt(Eigen::Vector3d(0.2, 0, 3), Eigen::Vector3d(0, 0.1, -1), Eigen::Vector3d(0, 1, 0));
}

// Every pixel of a tilted plane has the depth and normal of the analytic ray-plane intersection.
TEST(RaycastScene, TiltedPlaneHasExactDepthAndNormal) {
  const Eigen::Vector3d plane_point(0.3, -0.2, 4.0);
  const Eigen::Vector3d plane_normal = Eigen::Vector3d(0.2, -0.3, -1.0).normalized();
  const RaycastScene scene(PlaneMesh(plane_point, plane_normal));
  const Rigid3d cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.1, 0.2, 0.0), Eigen::Vector3d(0.1, 0.05, 1.0),
                                        Eigen::Vector3d(0, 1, 0));
  const Camera camera = DistortedCamera();
  const CameraRays rays(camera);
  GeometryMapsOptions options;
  options.barycentrics = true;
  const GeometryMaps maps = scene.Render(rays, cam_from_world, options);

  const Eigen::Matrix3d rotation = cam_from_world.rotation.toRotationMatrix();
  const Eigen::Vector3d normal_in_cam = rotation * plane_normal;
  const Eigen::Vector3d point_in_cam = cam_from_world * plane_point;
  for (int row = 0; row < 120; ++row) {
    for (int col = 0; col < 160; ++col) {
      const Eigen::Vector3d ray = camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5));  // z = 1
      const double expected_z = normal_in_cam.dot(point_in_cam) / normal_in_cam.dot(ray);
      ASSERT_NEAR(maps.depth.at<float>(row, col), expected_z, 2e-5 * expected_z) << col << "," << row;
      const cv::Vec3f n = maps.normal.at<cv::Vec3f>(row, col);
      const Eigen::Vector3d facing = normal_in_cam.dot(ray) < 0 ? normal_in_cam : -normal_in_cam;
      ASSERT_NEAR(n[0], facing.x(), 1e-5);
      ASSERT_NEAR(n[1], facing.y(), 1e-5);
      ASSERT_NEAR(n[2], facing.z(), 1e-5);
      ASSERT_GE(maps.face_id.at<int>(row, col), 0);
    }
  }
}

// The face id and barycentrics reproduce the hit point: (1-b1-b2) v0 + b1 v1 + b2 v2 = z * ray.
TEST(RaycastScene, BarycentricsReproduceTheHitPoint) {
  const Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.3 * std::sin(x) * std::cos(y); },
                                        -5, 5, -5, 5, 40, 40);
  const RaycastScene scene(mesh);
  const Rigid3d cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0.1, 0, -1), Eigen::Vector3d(0, 1, 0));
  const Camera camera = Camera::Pinhole(1, 64, 48, 40, 40);
  GeometryMapsOptions options;
  options.barycentrics = true;
  const GeometryMaps maps = scene.Render(CameraRays(camera), cam_from_world, options);
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  for (int row = 0; row < 48; row += 3) {
    for (int col = 0; col < 64; col += 3) {
      const int face_id = maps.face_id.at<int>(row, col);
      ASSERT_GE(face_id, 0);
      const Mesh::Face& face = mesh.faces[face_id];
      const cv::Vec2f b = maps.barycentrics.at<cv::Vec2f>(row, col);
      const Eigen::Vector3d from_barycentrics = (1.0 - b[0] - b[1]) * mesh.vertices[face[0]] +
                                                b[0] * mesh.vertices[face[1]] + b[1] * mesh.vertices[face[2]];
      const Eigen::Vector3d from_depth =
          world_from_cam * (maps.depth.at<float>(row, col) * camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5)));
      EXPECT_LT((from_barycentrics - from_depth).norm(), 1e-4);
    }
  }
}

// A unit cube 2 m in front of the camera: its front face is at depth 2 with normal -z; pixels outside
// its image are NaN / -1.
TEST(RaycastScene, UnitCubeFrontFace) {
  const RaycastScene scene(MakeBoxMesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)));
  const Rigid3d cam_from_world(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.5, -0.5, 2.0));
  const Camera camera = Camera::Pinhole(1, 100, 100, 100, 100);  // the face spans pixels 25..75
  const GeometryMaps maps = scene.Render(CameraRays(camera), cam_from_world);
  for (int row = 0; row < 100; ++row) {
    for (int col = 0; col < 100; ++col) {
      const bool inside = col + 0.5 > 25 && col + 0.5 < 75 && row + 0.5 > 25 && row + 0.5 < 75;
      const float z = maps.depth.at<float>(row, col);
      if (inside) {
        ASSERT_NEAR(z, 2.0f, 1e-6f);
        ASSERT_NEAR(maps.normal.at<cv::Vec3f>(row, col)[2], -1.0f, 1e-6f);
      } else {
        ASSERT_TRUE(std::isnan(z)) << col << "," << row;
        ASSERT_EQ(maps.face_id.at<int>(row, col), -1);
      }
    }
  }
}

// A tessellated sphere agrees with the analytic sphere to within its tessellation error: a facet of a
// 128 x 256 latitude-longitude sphere lies within R (1 - cos(pi/256) cos(pi/256)) = 1.5e-4 R of the sphere,
// and a ray away from the silhouette meets it within a few times that.
TEST(RaycastScene, SphereDepthAndNormalMatchAnalyticSphere) {
  const double radius = 1.0;
  const RaycastScene scene(MakeSphereMesh(Eigen::Vector3d::Zero(), radius, 128, 256));
  const Eigen::Vector3d centre(0, 0, -3);
  const Rigid3d cam_from_world(Eigen::Quaterniond::Identity(), -centre);
  const Camera camera = Camera::Pinhole(1, 80, 80, 80, 80);
  const GeometryMaps maps = scene.Render(CameraRays(camera), cam_from_world);
  int hits = 0;
  for (int row = 0; row < 80; ++row) {
    for (int col = 0; col < 80; ++col) {
      const Eigen::Vector3d d = camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5)).normalized();
      // |c + t d|^2 = R^2 with c the camera centre relative to the sphere centre.
      const double b = centre.dot(d), c = centre.squaredNorm() - radius * radius;
      const double discriminant = b * b - c;
      const float z = maps.depth.at<float>(row, col);
      if (discriminant < 0.01) continue;  // skip the silhouette, where facets and sphere disagree most
      ++hits;
      const double t = -b - std::sqrt(discriminant);
      EXPECT_NEAR(z, t * d.z(), 1e-3 * radius);
      const Eigen::Vector3d expected_normal = (centre + t * d).normalized();
      const cv::Vec3f n = maps.normal.at<cv::Vec3f>(row, col);
      EXPECT_GT(expected_normal.dot(Eigen::Vector3d(n[0], n[1], n[2])), std::cos(1.5 * M_PI / 180.0));
    }
  }
  EXPECT_GT(hits, 1000);
}

// A coarse sphere (15-degree facets) with radial vertex normals shades smoothly: the normal map follows
// the sphere through the point hit, where the facets' own normals are off by up to half a facet.
TEST(RaycastScene, VertexNormalsGiveSmoothShadingNormals) {
  Mesh sphere = MakeSphereMesh(Eigen::Vector3d::Zero(), 1.0, 12, 24);
  const Camera camera = Camera::Pinhole(1, 80, 80, 80, 80);
  const Rigid3d cam_from_world(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 3));
  const auto mean_angle_to_the_sphere = [&](const Mesh& mesh) {
    const RaycastScene scene(mesh);
    const GeometryMaps maps = scene.Render(CameraRays(camera), cam_from_world);
    double sum = 0.0;
    int count = 0;
    for (int row = 0; row < 80; ++row) {
      for (int col = 0; col < 80; ++col) {
        const float z = maps.depth.at<float>(row, col);
        if (std::isnan(z)) continue;
        const Eigen::Vector3d point_in_cam = z * camera.CamFromImg(Eigen::Vector2d(col + 0.5, row + 0.5));
        const Eigen::Vector3d radial = (point_in_cam - Eigen::Vector3d(0, 0, 3)).normalized();  // sphere centre
        if (radial.z() > -0.5) continue;  // away from the silhouette (at radial.z = -0.33)
        const cv::Vec3f n = maps.normal.at<cv::Vec3f>(row, col);
        sum += std::acos(std::min(1.0, radial.dot(Eigen::Vector3d(n[0], n[1], n[2])))) * 180.0 / M_PI;
        ++count;
      }
    }
    EXPECT_GT(count, 1000);
    return sum / count;
  };
  const double faceted = mean_angle_to_the_sphere(sphere);
  for (const Eigen::Vector3d& vertex : sphere.vertices) sphere.vertex_normals.push_back(vertex.normalized().cast<float>());
  const double smooth = mean_angle_to_the_sphere(sphere);
  std::printf("mean angle to the sphere's normal: faceted %.2f deg, vertex normals %.2f deg\n", faceted, smooth);
  EXPECT_GT(faceted, 2.0);
  EXPECT_LT(smooth, 0.5);
}

// Same maps, bit for bit, at any thread count.
TEST(RaycastScene, ResultsDoNotDependOnTheThreadCount) {
  const Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return std::sin(3 * x) * std::cos(2 * y); },
                                        -3, 3, -3, 3, 60, 60);
  const RaycastScene scene(mesh);
  const Rigid3d cam_from_world = CamFromWorldLookingAt(Eigen::Vector3d(0.2, 0, 4), Eigen::Vector3d(0, 0.1, -1), Eigen::Vector3d(0, 1, 0));
  const CameraRays rays(DistortedCamera(), 3);
  GeometryMapsOptions one, many;
  one.num_threads = 1;
  many.num_threads = 2;
  const GeometryMaps a = scene.Render(rays, cam_from_world, one);
  const GeometryMaps b = scene.Render(rays, cam_from_world, many);
  EXPECT_EQ(cv::norm(a.face_id, b.face_id, cv::NORM_INF), 0.0);
  cv::Mat depth_a = a.depth.clone(), depth_b = b.depth.clone();
  cv::patchNaNs(depth_a, -1);
  cv::patchNaNs(depth_b, -1);
  EXPECT_EQ(cv::norm(depth_a, depth_b, cv::NORM_INF), 0.0);
}

// Adaptive casting (samples every second pixel, planes in between) gives the maps of casting every pixel:
// the same face everywhere and the same depth to float precision, on a bumpy terrain with a boulder seen
// through a distorted camera (silhouettes and triangle edges included).
TEST(RaycastScene, AdaptiveCastingEqualsCastingEveryPixel) {
  const RaycastScene scene(TerrainWithBoulder());
  const Rigid3d cam_from_world = LookingDownAtTheTerrain();
  const CameraRays rays(DistortedCamera());
  GeometryMapsOptions full, adaptive;
  full.adaptive = false;
  full.barycentrics = adaptive.barycentrics = true;
  const GeometryMaps a = scene.Render(rays, cam_from_world, full);
  const GeometryMaps b = scene.Render(rays, cam_from_world, adaptive);
  EXPECT_EQ(cv::countNonZero(a.face_id != b.face_id), 0);
  for (int row = 0; row < a.depth.rows; ++row) {
    for (int col = 0; col < a.depth.cols; ++col) {
      const float za = a.depth.at<float>(row, col), zb = b.depth.at<float>(row, col);
      if (std::isnan(za)) {
        ASSERT_TRUE(std::isnan(zb));
        continue;
      }
      ASSERT_NEAR(zb, za, 2e-6f * za) << col << "," << row;
      const cv::Vec3f na = a.normal.at<cv::Vec3f>(row, col), nb = b.normal.at<cv::Vec3f>(row, col);
      ASSERT_LT(cv::norm(na - nb), 1e-5);
      const cv::Vec2f ba = a.barycentrics.at<cv::Vec2f>(row, col), bb = b.barycentrics.at<cv::Vec2f>(row, col);
      ASSERT_LT(cv::norm(ba - bb), 1e-4);
    }
  }
}

// Maps reused from another image hold nothing of it: rendering a view that sees the boulder against open
// water into maps last filled by a view of the terrain gives the maps of rendering it fresh, misses
// included; options not requested are dropped.
TEST(RaycastScene, RenderingIntoReusedMapsEqualsRenderingFresh) {
  const RaycastScene scene(TerrainWithBoulder());
  const CameraRays rays(DistortedCamera());
  const Rigid3d terrain_view = LookingDownAtTheTerrain();
  const Rigid3d sideways_view =
      CamFromWorldLookingAt(Eigen::Vector3d(-2.5, 0.2, 0.5), Eigen::Vector3d(1, 0, 0.15), Eigen::Vector3d(0, 0, 1));
  GeometryMapsOptions with_barycentrics;
  with_barycentrics.barycentrics = true;
  GeometryMaps reused;
  scene.Render(rays, terrain_view, with_barycentrics, &reused);
  scene.Render(rays, sideways_view, GeometryMapsOptions(), &reused);
  const GeometryMaps fresh = scene.Render(rays, sideways_view);
  const int misses = cv::countNonZero(fresh.face_id < 0);
  ASSERT_GT(misses, 100);  // open water above the horizon
  ASSERT_GT(cv::countNonZero(fresh.face_id >= 0), 100);
  EXPECT_EQ(cv::countNonZero(reused.face_id != fresh.face_id), 0);
  // NaN (not equal to itself) exactly where nothing is hit.
  EXPECT_EQ(cv::countNonZero(reused.depth == reused.depth), static_cast<int>(reused.depth.total()) - misses);
  cv::Mat depth_reused = reused.depth.clone(), depth_fresh = fresh.depth.clone();
  cv::patchNaNs(depth_reused, -1);
  cv::patchNaNs(depth_fresh, -1);
  EXPECT_EQ(cv::norm(depth_reused, depth_fresh, cv::NORM_INF), 0.0);
  EXPECT_TRUE(reused.barycentrics.empty());
}

// A window renders what the whole image shows at those pixels (an odd corner moves to the even pixel
// before it; the whole image's far edges and a window's far edges are the only places allowed to differ,
// here neither within two pixels is compared); a window off the image renders nothing.
TEST(RaycastScene, AWindowRendersWhatTheWholeImageShowsThere) {
  const RaycastScene scene(TerrainWithBoulder());
  const Rigid3d cam_from_world = LookingDownAtTheTerrain();
  const CameraRays rays(DistortedCamera());
  const GeometryMaps whole = scene.Render(rays, cam_from_world);
  EXPECT_EQ(whole.origin, cv::Point(0, 0));
  for (const cv::Rect& window : {cv::Rect(37, 21, 50, 41), cv::Rect(120, 90, 100, 100), cv::Rect(-5, -5, 30, 20)}) {
    GeometryMapsOptions options;
    options.window = window;
    const GeometryMaps part = scene.Render(rays, cam_from_world, options);
    const cv::Rect clipped = window & cv::Rect(0, 0, 160, 120);
    EXPECT_EQ(part.origin, cv::Point(clipped.x - clipped.x % 2, clipped.y - clipped.y % 2));
    EXPECT_EQ(part.origin.x + part.depth.cols, clipped.x + clipped.width);
    EXPECT_EQ(part.origin.y + part.depth.rows, clipped.y + clipped.height);
    int compared = 0;
    for (int row = part.origin.y; row < clipped.y + clipped.height - 2; ++row) {
      for (int col = part.origin.x; col < clipped.x + clipped.width - 2; ++col) {
        const int map_row = row - part.origin.y, map_col = col - part.origin.x;
        ASSERT_EQ(part.face_id.at<int>(map_row, map_col), whole.face_id.at<int>(row, col)) << col << "," << row;
        const float z_part = part.depth.at<float>(map_row, map_col), z_whole = whole.depth.at<float>(row, col);
        if (std::isnan(z_whole)) {
          ASSERT_TRUE(std::isnan(z_part));
        } else {
          ASSERT_EQ(z_part, z_whole) << col << "," << row;
          const cv::Vec3f n_part = part.normal.at<cv::Vec3f>(map_row, map_col);
          ASSERT_EQ(cv::norm(n_part - whole.normal.at<cv::Vec3f>(row, col)), 0.0);
        }
        ++compared;
      }
    }
    EXPECT_GT(compared, 200);
  }
  GeometryMapsOptions off_image;
  off_image.window = cv::Rect(500, 500, 10, 10);
  const GeometryMaps nothing = scene.Render(rays, cam_from_world, off_image);
  EXPECT_TRUE(nothing.depth.empty());
  EXPECT_TRUE(nothing.face_id.empty());
}

// Casting listed pixels alone gives the depth that casting every pixel gives them, NaN for misses and for
// pixels off the image, in the order listed.
TEST(RaycastScene, CastDepthsEqualCastingEveryPixel) {
  const RaycastScene scene(TerrainWithBoulder());
  const Rigid3d cam_from_world = LookingDownAtTheTerrain();
  const CameraRays rays(DistortedCamera());
  GeometryMapsOptions every_pixel;
  every_pixel.adaptive = false;
  const GeometryMaps maps = scene.Render(rays, cam_from_world, every_pixel);
  std::vector<cv::Point> pixels;
  for (int row = 119; row >= 0; row -= 3) {
    for (int col = 0; col < 160; col += 7) pixels.emplace_back(col, row);
  }
  pixels.emplace_back(-1, 5);
  pixels.emplace_back(160, 5);
  pixels.emplace_back(3, 120);
  std::vector<float> depths;
  scene.CastDepths(rays, cam_from_world, pixels, &depths);
  ASSERT_EQ(depths.size(), pixels.size());
  int hits = 0, misses = 0;
  for (std::size_t i = 0; i + 3 < pixels.size(); ++i) {
    const float expected = maps.depth.at<float>(pixels[i].y, pixels[i].x);
    if (std::isnan(expected)) {
      ASSERT_TRUE(std::isnan(depths[i])) << pixels[i];
      ++misses;
    } else {
      ASSERT_NEAR(depths[i], expected, 1e-6f * expected) << pixels[i];
      ++hits;
    }
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 5);  // the view sees past the terrain's corners
  for (std::size_t i = pixels.size() - 3; i < pixels.size(); ++i) EXPECT_TRUE(std::isnan(depths[i])) << pixels[i];
}

// Large (georeferenced) coordinates keep millimetre depth precision thanks to the local origin.
TEST(RaycastScene, GeoreferencedCoordinatesKeepPrecision) {
  const Eigen::Vector3d offset(512345.0, 6012345.0, -1500.0);
  const RaycastScene scene(PlaneMesh(offset + Eigen::Vector3d(0, 0, -2.0), Eigen::Vector3d::UnitZ()));
  const Rigid3d cam_from_world = CamFromWorldLookingAt(offset, Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 1, 0));
  const GeometryMaps maps = scene.Render(CameraRays(Camera::Pinhole(1, 40, 30, 30, 30)), cam_from_world);
  EXPECT_NEAR(maps.depth.at<float>(15, 20), 2.0f, 1e-3f);
}

TEST(RaycastScene, SingleRayIntersection) {
  const RaycastScene scene(MakeBoxMesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)));
  const RayHit hit = scene.Intersect(Eigen::Vector3d(0.5, 0.5, 5), Eigen::Vector3d(0, 0, -1));
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.distance, 4.0, 1e-6);
  EXPECT_NEAR(hit.normal_in_world.z(), 1.0, 1e-9);
  EXPECT_FALSE(scene.Intersect(Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(0, 0, 1)).hit);
}

TEST(RaycastScene, EmptyMeshAndBadPoseAreErrors) {
  const Mesh empty;
  EXPECT_THROW(RaycastScene{empty}, std::runtime_error);
  const RaycastScene scene(MakeBoxMesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)));
  Rigid3d pose;
  pose.translation.x() = std::nan("");
  EXPECT_THROW(scene.Render(CameraRays(Camera::Pinhole(1, 8, 8, 8, 8)), pose), std::invalid_argument);
}

}  // namespace
}  // namespace lutex
