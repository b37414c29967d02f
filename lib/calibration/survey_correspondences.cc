#include "lib/calibration/survey_correspondences.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "lib/raycast/forward_scatter_removal.h"
#include "lib/raycast/images_by_camera.h"

namespace lutex {

namespace {

struct ImageSamples {
  std::vector<SurfaceSample> samples;
  std::vector<Eigen::Vector3d> points_in_world;
  std::vector<double> footprints_in_world;  // radius, scene units
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();
};

// A sample's view found in a candidate partner: which sample, which candidate (its rank), and the view.
struct Match {
  std::size_t sample = 0;
  std::size_t rank = 0;
  SurfaceView view;
};

}  // namespace

std::map<std::uint32_t, std::vector<std::uint32_t>> CandidatePartners(
    const SparseModel& model, const std::map<std::uint32_t, Eigen::Vector3d>& look_at_by_image, std::size_t count) {
  std::map<std::uint32_t, std::map<std::uint32_t, std::size_t>> shared;
  for (const auto& [id, point] : model.points3D) {
    for (std::size_t i = 0; i < point.track.size(); ++i) {
      for (std::size_t j = 0; j < point.track.size(); ++j) {
        if (point.track[i].image_id != point.track[j].image_id) ++shared[point.track[i].image_id][point.track[j].image_id];
      }
    }
  }
  std::map<std::uint32_t, std::vector<std::uint32_t>> candidates;
  for (const auto& [a, a_look_at] : look_at_by_image) {
    // (rank class, score, image), smaller first: images sharing points (most first), then the rest by
    // the distance between look-at points.
    std::vector<std::tuple<int, double, std::uint32_t>> ranked;
    const auto a_shared = shared.find(a);
    for (const auto& [b, b_look_at] : look_at_by_image) {
      if (b == a) continue;
      std::size_t common = 0;
      if (a_shared != shared.end()) {
        const auto found = a_shared->second.find(b);
        if (found != a_shared->second.end()) common = found->second;
      }
      if (common > 0) {
        ranked.emplace_back(0, -static_cast<double>(common), b);
      } else {
        ranked.emplace_back(1, (b_look_at - a_look_at).norm(), b);
      }
    }
    std::sort(ranked.begin(), ranked.end());
    for (std::size_t i = 0; i < std::min(count, ranked.size()); ++i) candidates[a].push_back(std::get<2>(ranked[i]));
  }
  return candidates;
}

void SurveyCorrespondenceOptions::Check() const {
  superpixels.Check();
  views.Check();
  forward_scatter.Check();
  if (partners < 1 || candidates < partners) throw std::invalid_argument("need 1 <= partners <= candidates");
}

SurveyCorrespondences ExtractSurveyCorrespondences(const std::filesystem::path& images_dir, const SparseModel& model,
                                                   const RaycastScene& scene,
                                                   const SurveyCorrespondenceOptions& options) {
  options.Check();
  // Each view's `image` indexes image_paths, the model's images in id order.
  std::vector<std::filesystem::path> image_paths;
  std::map<std::uint32_t, int> image_index;
  for (const auto& [id, image] : model.images) {
    image_index[id] = static_cast<int>(image_paths.size());
    image_paths.push_back(images_dir / image.name);
  }
  std::map<std::uint32_t, ImageSamples> samples;
  std::mutex mutex;
  ForEachImageWithMaps(model, scene, options.num_threads, "superpixels",
                       [&](const Image& image, const CameraRays& rays, const GeometryMaps& maps, int) {
    const cv::Mat observed = WithoutForwardScatter(ReadLinearImage(images_dir / image.name, options.input_encoding),
                                                   maps, rays, options.forward_scatter,
                                                   options.superpixels.saturation_level,
                                                   options.backscatter.For(maps, images_dir, image.name));
    ImageSamples result;
    result.samples = SampleSuperpixels(observed, maps, rays, options.superpixels);
    const Rigid3d world_from_cam = image.cam_from_world.Inverse();
    for (SurfaceSample& sample : result.samples) {
      sample.view.image = image_index.at(image.image_id);
      result.points_in_world.push_back(world_from_cam * sample.view.point_in_cam);
      result.footprints_in_world.push_back(sample.footprint_radius * sample.view.point_in_cam.z() /
                                           rays.camera().FocalLengthX());
      result.look_at += result.points_in_world.back() / static_cast<double>(result.samples.size());
    }
    std::lock_guard<std::mutex> lock(mutex);
    samples[image.image_id] = std::move(result);
  });
  std::map<std::uint32_t, Eigen::Vector3d> look_at_by_image;
  for (const auto& [id, image_samples] : samples) {
    if (!image_samples.samples.empty()) look_at_by_image[id] = image_samples.look_at;
  }
  const auto candidates = CandidatePartners(model, look_at_by_image, static_cast<std::size_t>(options.candidates));
  // Who asks image B: (image A, rank of B among A's candidates).
  std::map<std::uint32_t, std::vector<std::pair<std::uint32_t, std::size_t>>> askers;
  for (const auto& [a, list] : candidates) {
    for (std::size_t rank = 0; rank < list.size(); ++rank) askers[list[rank]].emplace_back(a, rank);
  }

  std::map<std::uint32_t, std::vector<Match>> matches;  // per image A
  // Only the images some other image asks.
  const SparseModel asked = OnlyImages(model, [&](const Image& image) { return askers.count(image.image_id) > 0; });
  ForEachImageWithMaps(asked, scene, options.num_threads, "correspondences",
                       [&](const Image& image, const CameraRays& rays, const GeometryMaps& maps, int) {
    const auto asking = askers.find(image.image_id);
    const cv::Mat observed = WithoutForwardScatter(ReadLinearImage(images_dir / image.name, options.input_encoding),
                                                   maps, rays, options.forward_scatter, options.views.saturation_level,
                                                   options.backscatter.For(maps, images_dir, image.name));
    const ViewedImage other{observed, maps, rays, image.cam_from_world};
    std::vector<std::pair<std::uint32_t, Match>> found;
    for (const auto& [a, rank] : asking->second) {
      const ImageSamples& a_samples = samples.at(a);
      for (std::size_t s = 0; s < a_samples.samples.size(); ++s) {
        if (auto view = ViewInOtherImage(a_samples.points_in_world[s], a_samples.footprints_in_world[s], other, options.views)) {
          view->image = image_index.at(image.image_id);
          found.emplace_back(a, Match{s, rank, *view});
        }
      }
    }
    std::lock_guard<std::mutex> lock(mutex);
    for (auto& [a, match] : found) matches[a].push_back(std::move(match));
  });

  SurveyCorrespondences result;
  result.images = std::move(image_paths);
  result.num_images = model.images.size();
  for (auto& [a, list] : matches) {
    // Deterministic: by sample, then candidate rank; the first `partners` per sample.
    std::sort(list.begin(), list.end(), [](const Match& x, const Match& y) {
      return x.sample != y.sample ? x.sample < y.sample : x.rank < y.rank;
    });
    const ImageSamples& a_samples = samples.at(a);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      kept = i > 0 && list[i].sample == list[i - 1].sample ? kept + 1 : 0;
      if (kept >= static_cast<std::size_t>(options.partners)) continue;
      result.correspondences.push_back({a_samples.samples[list[i].sample].view, list[i].view, Eigen::Vector3d::Ones()});
    }
  }
  for (const auto& [id, image_samples] : samples) result.num_samples += image_samples.samples.size();
  return result;
}

}  // namespace lutex
