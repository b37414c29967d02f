#include "lib/model/sparse_points.h"

#include <cmath>
#include <random>

#include "lib/util/parallel_for.h"

namespace lutex {

namespace {

struct Candidate {
  Eigen::Vector3d point_in_world;
  Eigen::Vector3d normal_in_world;
  std::uint32_t first_image = 0;
};

}  // namespace

std::size_t AddSimulatedSparsePoints(const RaycastScene& scene, const SparsePointsOptions& options, SparseModel* model) {
  if (options.points_per_image <= 0 || model->images.empty()) return 0;
  std::vector<Image*> images;
  for (auto& [id, image] : model->images) images.push_back(&image);
  // Surface points on a grid of each image's pixels.
  std::vector<std::vector<Candidate>> per_image(images.size());
  ParallelFor(images.size(), options.num_threads, [&](std::size_t i) {
    const Image& image = *images[i];
    const Camera& camera = model->cameras.at(image.camera_id);
    const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(double(options.points_per_image)))));
    const Eigen::Vector3d centre = image.cam_from_world.TargetOriginInSource();
    for (int r = 0; r < side; ++r) {
      for (int c = 0; c < side; ++c) {
        const Eigen::Vector2d pixel((c + 0.5) * double(camera.width) / side, (r + 0.5) * double(camera.height) / side);
        const Eigen::Vector3d ray = image.cam_from_world.rotation.inverse() * camera.CamFromImg(pixel);
        const RayHit hit = scene.Intersect(centre, ray.normalized());
        if (!hit.hit) continue;
        per_image[i].push_back({centre + hit.distance * ray.normalized(), hit.normal_in_world, image.image_id});
      }
    }
  });
  std::vector<Candidate> candidates;
  for (const auto& list : per_image) candidates.insert(candidates.end(), list.begin(), list.end());
  // Tracks: every image that sees the point, unoccluded and not grazing.
  std::vector<std::vector<std::pair<std::uint32_t, Eigen::Vector2d>>> tracks(candidates.size());
  ParallelFor(candidates.size(), options.num_threads, [&](std::size_t p) {
    const Candidate& candidate = candidates[p];
    for (const Image* image : images) {
      const Camera& camera = model->cameras.at(image->camera_id);
      const Eigen::Vector3d point_in_cam = image->cam_from_world * candidate.point_in_world;
      if (!(point_in_cam.z() > 0.0)) continue;
      const Eigen::Vector2d pixel = camera.ImgFromCam(point_in_cam);
      if (!(pixel.x() >= 0.0 && pixel.y() >= 0.0 && pixel.x() < double(camera.width) &&
            pixel.y() < double(camera.height))) {
        continue;
      }
      const Eigen::Vector3d centre = image->cam_from_world.TargetOriginInSource();
      const Eigen::Vector3d to_point = candidate.point_in_world - centre;
      const double distance = to_point.norm();
      if (std::abs(candidate.normal_in_world.dot(to_point / distance)) < 0.17) continue;
      const RayHit hit = scene.Intersect(centre, to_point / distance);
      if (!hit.hit || std::abs(hit.distance - distance) > 1e-4 * distance + 1e-6) continue;
      tracks[p].emplace_back(image->image_id, pixel);
    }
  });
  std::mt19937_64 random(options.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uint64_t next_id = model->points3D.empty() ? 1 : model->points3D.rbegin()->first + 1;
  std::size_t added = 0;
  for (std::size_t p = 0; p < candidates.size(); ++p) {
    const Eigen::Vector3d offset(noise(random), noise(random), noise(random));  // drawn for every point: seed-stable
    if (tracks[p].size() < 2) continue;
    Point3D point;
    point.point3D_id = next_id++;
    point.xyz = candidates[p].point_in_world + options.noise * offset;
    const Image& first = model->images.at(tracks[p].front().first);
    const Camera& camera = model->cameras.at(first.camera_id);
    const double range = (first.cam_from_world * point.xyz).z();
    point.error = range > 0.0 ? options.noise * camera.FocalLengthX() / range : 0.0;
    for (const auto& [image_id, pixel] : tracks[p]) {
      Image& image = model->images.at(image_id);
      point.track.push_back({image_id, static_cast<std::uint32_t>(image.points2D.size())});
      Point2D observation;
      observation.xy = pixel;
      observation.point3D_id = point.point3D_id;
      image.points2D.push_back(observation);
    }
    model->points3D[point.point3D_id] = point;
    ++added;
  }
  return added;
}

}  // namespace lutex
