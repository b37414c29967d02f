#pragma once

// Synthetic scenes for the texturing tests, and their views rendered exactly: each pixel shows a shader's
// colour at the surface point its ray hits (no light, no water: what a perfectly restored image shows).

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"
#include "texturing/texture_views.h"

namespace lutex {

using Shader = std::function<Eigen::Vector3f(int face, const Eigen::Vector3d& point_in_world)>;

// The view's image: the shader at the surface point each pixel's ray hits (black where it hits nothing).
inline cv::Mat RenderShaded(const RaycastScene& scene, const TextureView& view, const Shader& shader) {
  const CameraRays rays(view.camera, 1);
  GeometryMapsOptions options;
  options.num_threads = 1;
  const GeometryMaps maps = scene.Render(rays, view.cam_from_world, options);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  cv::Mat image(maps.depth.size(), CV_32FC3, cv::Scalar::all(0));
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      const int face = maps.face_id.at<int>(row, col);
      if (face < 0) continue;
      const Eigen::Vector3d ray = rays.Direction(col, row).cast<double>();
      const Eigen::Vector3f colour = shader(face, world_from_cam * (ray / ray.z() * double(maps.depth.at<float>(row, col))));
      image.at<cv::Vec3f>(row, col) = cv::Vec3f(colour.x(), colour.y(), colour.z());
    }
  }
  return image;
}

// Patches of 0.25 m, each of one colour in [0.05, 0.85]. Their edges are offset from the lines half way
// between cameras on a 0.5 m grid, where the charts of neighbouring views meet.
inline Eigen::Vector3f PatchworkAlbedo(const Eigen::Vector3d& point_in_world) {
  const int i = static_cast<int>(std::floor((point_in_world.x() + 0.13) / 0.25));
  const int j = static_cast<int>(std::floor((point_in_world.y() + 0.07) / 0.25));
  const unsigned hash = static_cast<unsigned>(i * 73856093) ^ static_cast<unsigned>(j * 19349663);
  return {0.05f + 0.8f * float(hash % 97) / 96.0f, 0.05f + 0.8f * float((hash / 97) % 89) / 88.0f,
          0.05f + 0.8f * float((hash / 8633) % 83) / 82.0f};
}

inline cv::Mat RenderPatchwork(const RaycastScene& scene, const TextureView& view) {
  return RenderShaded(scene, view, [](int, const Eigen::Vector3d& point) { return PatchworkAlbedo(point); });
}

// A 2 x 2 m seafloor of 5 cm cells (two faces each) with a boulder 0.35 m high at (0.2, 0.1) that hides
// part of the floor from oblique views.
inline Mesh BoulderFloor() {
  return MakeHeightFieldMesh(
      [](double x, double y) {
        return 0.35 * std::exp(-((x - 0.2) * (x - 0.2) + (y - 0.1) * (y - 0.1)) / (2 * 0.15 * 0.15)) +
               0.03 * std::sin(3.0 * x) * std::cos(2.0 * y);
      },
      -1.0, 1.0, -1.0, 1.0, 40, 40);
}

// Nine views of `camera` from 1.5 m on a 0.6 m grid, each looking at a point between itself and the
// centre: the outer ones obliquely.
inline std::vector<TextureView> NineViewsOfTheCentre(const Camera& camera) {
  std::vector<TextureView> views;
  for (double y : {-0.6, 0.0, 0.6}) {
    for (double x : {-0.6, 0.0, 0.6}) {
      const Eigen::Vector3d centre(x, y, 1.5), target(0.4 * x, 0.4 * y, 0.0);
      views.push_back({"view_" + std::to_string(views.size()), camera,
                       CamFromWorldLookingAt(centre, (target - centre).normalized(), Eigen::Vector3d::UnitY())});
    }
  }
  return views;
}

}  // namespace lutex
