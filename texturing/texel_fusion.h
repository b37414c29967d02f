#pragma once

// The colour of every texel, from the views that see its surface point.
//
// Each view that is a candidate of a face (FaceViewCandidates) is sampled at the projection of the
// face's texels: bilinearly, over the pixels whose ray-cast depth agrees with the texel's depth (so
// occluded views and pixels across an occluding edge give nothing). A sample's weight is the pixel's
// confidence x the cosine of the viewing angle x (focal length / depth)^2: trusted, frontal,
// high-resolution views count most. Each texel keeps its `kSamplesPerTexel` heaviest samples.
//
// Blend modes:
//   kFuse    a robust weighted mean: with three or more samples, those further than 0.02 + 0.15 x the
//            brightest channel from the per-channel weighted median are rejected (particles, specular
//            highlights, a view's misregistration); with two, only a gross difference (0.1 + 0.5 x the
//            brightest channel) rejects the sample of the view the MRF did not choose. The default.
//   kSingle  the view the MRF chose for the face (like the texturers that keep one view per face);
//            where that view does not see the texel (partly occluded face), the heaviest sample.
//
// Memory: kSamplesPerTexel samples per texel for the texels of one pass; the atlas is done in as many
// passes over the views as `memory_limit_bytes` needs. Each pass takes neighbouring charts (one part of
// the surface), reads only the views that see them and ray casts only the rectangle of each view their
// faces project to, or, where its texels are few in that rectangle (seam points scattered over a whole
// view), only the pixels they read (view_pixel_depths.h). Results do not depend on the passes. A pass's
// samples are held in blocks of 1 MiB (lib/util/chunked_array.h), not one block of tens of MB, so that a
// tiled bake, which fuses tile after tile, finds room for them in what earlier tiles freed.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lib/geometry/mesh.h"
#include "texturing/face_view_candidates.h"
#include "texturing/texel_layout.h"
#include "texturing/texture_views.h"

namespace lutex {

enum class TexelBlend { kFuse, kSingle };

// "fuse" or "single"; throws std::invalid_argument otherwise.
TexelBlend ParseTexelBlend(const std::string& name);

constexpr int kSamplesPerTexel = 4;

struct TexelFusionOptions {
  TexelBlend blend = TexelBlend::kFuse;
  // Bound on the sample buffers of one pass (the texture baker's bound on a batch's texel table and
  // samples together).
  std::size_t memory_limit_bytes = std::size_t{2} << 30;
  int num_threads = 0;
  // Progress over the views on stderr; off for callers that fuse many small layouts and report their own.
  bool show_progress = true;
  // What the progress line says it is doing.
  std::string progress_label = "texture: colours";
};

struct TexelFusionSummary {
  int num_passes = 0;
  std::size_t views_read = 0;  // images read, over all passes
  std::size_t views_cast_by_pixel = 0;  // of those, cast only at the pixels their texels read
  std::size_t num_texels = 0;
  std::size_t texels_without_samples = 0;  // no view sees them: filled from their neighbours
  std::size_t rejected_samples = 0;
  double mean_samples_per_texel = 0.0;

  // Adds the counts of another fusion (of other texels) to these.
  void Add(const TexelFusionSummary& other);
};

// Bytes of sample buffer per texel of a pass: a pass takes `memory_limit_bytes` / this many texels.
std::size_t FusionBytesPerTexel();

// Writes the colour of every texel into `pages` (linear RGB CV_32FC3 of the layout's page sizes); texels
// no view sees are NaN.
TexelFusionSummary FuseTexels(const Mesh& mesh, const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                              const ViewImageSource& source, const FaceViewCandidates& candidates,
                              const std::vector<std::uint32_t>& view_of_face, const TexelLayout& layout,
                              const TexelFusionOptions& options, std::vector<cv::Mat>& pages);

}  // namespace lutex
