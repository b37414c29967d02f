#include "lib/model/simulator.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "lib/model/forward_scatter.h"
#include "lib/util/parallel_for.h"

namespace lutex {

void SimulatorOptions::Check() const {
  if (backscatter_steps < 1) throw std::invalid_argument("backscatter_steps must be at least 1");
  if (!(max_range > 0.0)) throw std::invalid_argument("max_range must be positive");
  if (!(water_start > 0.0) || water_start >= max_range) throw std::invalid_argument("water_start must be in (0, max_range)");
}

Simulator::Simulator(const Mesh& mesh, const LightRig& rig, const Water& water, const SurfaceAlbedo& albedo,
                     const SimulatorOptions& options)
    : mesh_(mesh), rig_(rig), water_(water), albedo_(albedo), options_(options) {
  if (!mesh.faces.empty()) scene_ = std::make_unique<RaycastScene>(mesh);
  options_.Check();
  if (rig_.lights.empty()) throw std::invalid_argument("the light rig has no lights");
}

Eigen::Vector3d Simulator::LightTerm(const Light& light, const Eigen::Vector3d& point_in_cam,
                                     Eigen::Vector3d* to_light) const {
  const Eigen::Vector3d offset = light.position_in_cam - point_in_cam;
  const double distance = offset.norm();
  *to_light = offset / distance;
  const double cos_psi = -light.direction_in_cam.dot(*to_light);
  const double profile = light.Profile(cos_psi);
  if (profile <= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Array3d transmission = (-water_.Attenuation().array() * distance).exp();
  return (light.intensity.array() * transmission * (profile / (distance * distance))).matrix();
}

Eigen::Array3d Simulator::BackscatterDensity(const Eigen::Vector3d& direction_in_cam, double s) const {
  const Eigen::Vector3d point = s * direction_in_cam;
  Eigen::Array3d in_scattered = Eigen::Array3d::Zero();
  for (const Light& light : rig_.lights) {
    Eigen::Vector3d to_light;
    const Eigen::Vector3d term = LightTerm(light, point, &to_light);
    // Light propagates along -to_light and scatters towards the camera, along -direction.
    in_scattered += term.array() * HenyeyGreenstein(to_light.dot(direction_in_cam), water_.anisotropy_g);
  }
  return in_scattered * water_.scattering.array() * (-water_.Attenuation().array() * s).exp();
}

Eigen::Vector3d Simulator::Backscatter(const Eigen::Vector3d& direction_in_cam, double range) const {
  if (water_.scattering.isZero()) return Eigen::Vector3d::Zero();
  const double start = options_.water_start, s0 = start;
  if (range <= start) return Eigen::Vector3d::Zero();
  const double step = std::log1p((range - start) / s0) / options_.backscatter_steps;
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  for (int k = 0; k < options_.backscatter_steps; ++k) {
    const double w = (k + 0.5) * step;
    sum += BackscatterDensity(direction_in_cam, start + s0 * std::expm1(w)) * s0 * std::exp(w) * step;
  }
  return sum.matrix();
}

GeometryMaps Simulator::RenderGeometry(const CameraRays& rays, const Rigid3d& cam_from_world,
                                  const GeometryMapsOptions& options) const {
  if (scene_) return scene_->Render(rays, cam_from_world, options);
  // Pure water: nothing is hit anywhere.
  GeometryMaps maps;
  maps.depth = cv::Mat(rays.height(), rays.width(), CV_32F, cv::Scalar(std::nan("")));
  maps.face_id = cv::Mat(rays.height(), rays.width(), CV_32S, cv::Scalar(-1));
  return maps;
}

BackscatterTable Simulator::MakeBackscatterTable(const CameraRays& rays) const {
  BackscatterTableOptions table_options;
  table_options.scale = options_.water_start;
  // Backscatter changes smoothly with the ray direction: a grid node every ~1.1 degrees is plenty.
  const double focal = std::min(rays.camera().FocalLengthX(), rays.camera().FocalLengthY());
  table_options.pixel_stride = std::max(1, static_cast<int>(0.02 * focal));
  table_options.max_range = options_.max_range;
  table_options.start = options_.water_start;
  table_options.num_threads = options_.num_threads;
  if (water_.scattering.isZero()) table_options.num_steps = 1;
  return BackscatterTable(rays.camera(),
                          [this](const Eigen::Vector3d& direction, double s) { return BackscatterDensity(direction, s); },
                          table_options);
}

Eigen::Vector3d Simulator::SignalFactor(const Eigen::Vector3d& point_in_cam) const {
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  for (const Light& light : rig_.lights) {
    Eigen::Vector3d to_light;
    sum += LightTerm(light, point_in_cam, &to_light).array();
  }
  const Eigen::Array3d to_camera = (-water_.Attenuation().array() * point_in_cam.norm()).exp();
  return (sum * to_camera / M_PI).matrix();
}

cv::Mat Simulator::Render(const CameraRays& rays, const Rigid3d& cam_from_world) const {
  return Render(rays, MakeBackscatterTable(rays), cam_from_world);
}

cv::Mat Simulator::Render(const CameraRays& rays, const BackscatterTable& backscatter,
                          const Rigid3d& cam_from_world) const {
  GeometryMapsOptions map_options;
  map_options.barycentrics = true;
  map_options.num_threads = options_.num_threads;
  const GeometryMaps maps = RenderGeometry(rays, cam_from_world, map_options);
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  // The direct term and the backscatter apart, so that forward scattering spreads only the former.
  cv::Mat radiance(rays.height(), rays.width(), CV_32FC3, cv::Scalar::all(0));
  cv::Mat veil(rays.height(), rays.width(), CV_32FC3, cv::Scalar::all(0));
  cv::Mat range_map(rays.height(), rays.width(), CV_32F, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
  ParallelFor(static_cast<std::size_t>(rays.height()), options_.num_threads, [&](std::size_t row_index) {
    const int row = static_cast<int>(row_index);
    for (int col = 0; col < rays.width(); ++col) {
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      if (!direction.allFinite()) continue;
      const float depth = maps.depth.at<float>(row, col);
      Eigen::Vector3d value = Eigen::Vector3d::Zero(), scattered;
      if (std::isnan(depth)) {
        scattered = backscatter.Lookup(col + 0.5, row + 0.5, options_.max_range);
      } else {
        const double range = depth / direction.z();
        range_map.at<float>(row, col) = static_cast<float>(range);
        const Eigen::Vector3d point = range * direction;
        const int face = maps.face_id.at<int>(row, col);
        const cv::Vec2f b = maps.barycentrics.at<cv::Vec2f>(row, col);
        const cv::Vec3f shading = maps.normal.at<cv::Vec3f>(row, col);  // smooth where the mesh has normals
        const Eigen::Vector3d normal(shading[0], shading[1], shading[2]);
        const Eigen::Vector3d albedo = albedo_.At(mesh_, face, b[0], b[1]);
        Eigen::Array3d irradiance = Eigen::Array3d::Zero();
        for (const Light& light : rig_.lights) {
          Eigen::Vector3d to_light;
          const Eigen::Vector3d term = LightTerm(light, point, &to_light);
          const double cos_incidence = normal.dot(to_light);
          if (cos_incidence <= 0.0 || term.isZero()) continue;
          if (options_.shadows) {
            const Eigen::Vector3d origin = world_from_cam * (point + 1e-5 * (1.0 + range) * normal);
            const RayHit hit = scene_->Intersect(origin, world_from_cam * light.position_in_cam - origin);
            if (hit.hit && hit.distance < 1.0 - 1e-6) continue;
          }
          irradiance += term.array() * cos_incidence;
        }
        const Eigen::Array3d to_camera = (-water_.Attenuation().array() * range).exp();
        value = (irradiance * to_camera * albedo.array() / M_PI).matrix();
        scattered = backscatter.Lookup(col + 0.5, row + 0.5, range);
      }
      radiance.at<cv::Vec3f>(row, col) =
          cv::Vec3f(static_cast<float>(value.x()), static_cast<float>(value.y()), static_cast<float>(value.z()));
      veil.at<cv::Vec3f>(row, col) =
          cv::Vec3f(static_cast<float>(scattered.x()), static_cast<float>(scattered.y()), static_cast<float>(scattered.z()));
    }
  });
  if (options_.forward_scatter) {
    const ForwardScatter scatter = ForwardScatter::Of(water_);
    if (!scatter.IsNone()) {
      const Camera& camera = rays.camera();
      radiance = AddForwardScatter(radiance, range_map,
                                   MakeForwardScatterKernel(scatter.anisotropy_g,
                                                            0.5 * (camera.FocalLengthX() + camera.FocalLengthY())),
                                   scatter.scattering);
    }
  }
  return radiance + veil;
}

cv::Mat Simulator::RenderAlbedo(const CameraRays& rays, const Rigid3d& cam_from_world) const {
  GeometryMapsOptions map_options;
  map_options.normal = false;
  map_options.barycentrics = true;
  map_options.num_threads = options_.num_threads;
  const GeometryMaps maps = RenderGeometry(rays, cam_from_world, map_options);
  cv::Mat albedo(rays.height(), rays.width(), CV_32FC3, cv::Scalar::all(std::nan("")));
  ParallelFor(static_cast<std::size_t>(rays.height()), options_.num_threads, [&](std::size_t row_index) {
    const int row = static_cast<int>(row_index);
    for (int col = 0; col < rays.width(); ++col) {
      const int face = maps.face_id.at<int>(row, col);
      if (face < 0) continue;
      const cv::Vec2f b = maps.barycentrics.at<cv::Vec2f>(row, col);
      const Eigen::Vector3d value = albedo_.At(mesh_, face, b[0], b[1]);
      albedo.at<cv::Vec3f>(row, col) =
          cv::Vec3f(static_cast<float>(value.x()), static_cast<float>(value.y()), static_cast<float>(value.z()));
    }
  });
  return albedo;
}

FrustumLut Simulator::TrueLut(const Camera& camera, const FrustumLutGrid& grid) const {
  FrustumLut lut(grid);
  ParallelFor(static_cast<std::size_t>(grid.nz), options_.num_threads, [&](std::size_t k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        const Eigen::Vector3d ray = camera.CamFromImg(lut.NodePixel(i, j));  // z = 1
        const Eigen::Vector3d point = grid.SlabDepth(static_cast<int>(k)) * ray;
        LutNode& node = lut.node(i, j, static_cast<int>(k));
        node.alpha = SignalFactor(point);
        node.beta = Backscatter(ray.normalized(), point.norm());
      }
    }
  });
  return lut;
}

}  // namespace lutex
