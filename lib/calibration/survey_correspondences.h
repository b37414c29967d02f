#pragma once

// Correspondence observations from a survey (a sparse model, its images and its mesh), for `lutex calibrate
// --correspondences`. Two streamed passes over the images (each image read and ray-cast twice, one image
// per thread in memory):
//   1. superpixel samples of every image (superpixel_samples.h), kept as world points with footprints;
//   2. every image B looks up the samples of the images that chose B as a candidate partner
//      (correspondence_views.h).
// Candidate partners of image A: the `candidates` images sharing the most COLMAP 3-D points with A (the
// overlap graph of the reconstruction), filled up, when fewer share points with A (or the model has no
// tracks), by the images whose look-at points (the mean of their samples) are nearest to A's. A sample keeps its views in at most `partners`
// of them, in candidate order, so the number of correspondences grows linearly with the survey and the
// result does not depend on the thread count. Memory: the samples (about 300 per image) and the matches.

#include <cstddef>
#include <filesystem>
#include <map>
#include <vector>

#include "lib/geometry/sparse_model.h"
#include "lib/calibration/correspondence_views.h"
#include "lib/calibration/observations.h"
#include "lib/calibration/superpixel_samples.h"
#include "lib/image/image_io.h"
#include "lib/calibration/backscatter_set_aside.h"
#include "lib/model/forward_scatter.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

struct SurveyCorrespondenceOptions {
  SuperpixelOptions superpixels;
  CorrespondenceViewOptions views;
  int partners = 4;    // views per sample, at most (the paper pairs each superpixel with one image)
  int candidates = 8;  // images tried per image
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // Taken out of every image before it is sampled (lib/model/forward_scatter.h): the LUT's, with
  // `backscatter` set aside (backscatter_set_aside.h).
  ForwardScatter forward_scatter;
  BackscatterSetAside backscatter;
  int num_threads = 0;

  void Check() const;
};

struct SurveyCorrespondences {
  std::vector<CorrespondenceObservation> correspondences;
  // The model's images (images_dir / name) in id order; a view's `image` indexes this list.
  std::vector<std::filesystem::path> images;
  std::size_t num_images = 0;
  std::size_t num_samples = 0;
};

// The candidate partners of every image of `look_at_by_image` (images without samples are left out),
// best first, at most `count` each: images sharing COLMAP 3-D points (most shared first; ties by id),
// then the other images by the distance between look-at points.
std::map<std::uint32_t, std::vector<std::uint32_t>> CandidatePartners(
    const SparseModel& model, const std::map<std::uint32_t, Eigen::Vector3d>& look_at_by_image, std::size_t count);

// `images_dir`: the folder the model's image names are relative to.
SurveyCorrespondences ExtractSurveyCorrespondences(const std::filesystem::path& images_dir, const SparseModel& model,
                                                   const RaycastScene& scene,
                                                   const SurveyCorrespondenceOptions& options);

}  // namespace lutex
