#include "texturing/texel_fusion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

namespace {

struct TexelSample {
  Eigen::Vector3f colour = Eigen::Vector3f::Zero();
  float weight = 0.0f;
  std::uint32_t view = 0;
};

bool Heavier(const TexelSample& a, const TexelSample& b) {
  return a.weight > b.weight || (a.weight == b.weight && a.view < b.view);
}

// The heaviest samples of one texel, heaviest first; independent of the order they are offered in.
struct TexelSamples {
  std::array<TexelSample, kSamplesPerTexel> samples;
  std::uint8_t count = 0;

  void Offer(const TexelSample& sample) {
    if (count == kSamplesPerTexel && !Heavier(sample, samples[count - 1])) return;
    if (count < kSamplesPerTexel) ++count;
    int i = count - 1;
    while (i > 0 && Heavier(sample, samples[i - 1])) {
      samples[i] = samples[i - 1];
      --i;
    }
    samples[i] = sample;
  }
};

// Per-channel weighted median of the samples.
Eigen::Vector3f WeightedMedian(const TexelSamples& texel) {
  Eigen::Vector3f median;
  for (int c = 0; c < 3; ++c) {
    std::array<std::pair<float, float>, kSamplesPerTexel> values;
    float total = 0.0f;
    for (int i = 0; i < texel.count; ++i) {
      values[i] = {texel.samples[i].colour[c], texel.samples[i].weight};
      total += texel.samples[i].weight;
    }
    std::sort(values.begin(), values.begin() + texel.count);
    float below = 0.0f;
    median[c] = values[texel.count - 1].first;
    for (int i = 0; i < texel.count; ++i) {
      below += values[i].second;
      if (below >= 0.5f * total) {
        median[c] = values[i].first;
        break;
      }
    }
  }
  return median;
}

// The final colour of a texel whose face was given `chosen_view` by the view selection.
Eigen::Vector3f Blend(const TexelSamples& texel, std::uint32_t chosen_view, TexelBlend blend, std::size_t* rejected) {
  const TexelSample* chosen = nullptr;
  for (int i = 0; i < texel.count; ++i) {
    if (texel.samples[i].view == chosen_view) chosen = &texel.samples[i];
  }
  if (blend == TexelBlend::kSingle) return chosen ? chosen->colour : texel.samples[0].colour;
  // With three or more samples the median tells outliers apart; with two, only a gross difference
  // (a particle, a highlight) is one, and the view the MRF chose is then kept. Rejecting milder
  // differences would make each chart keep its own view near its border, which is a seam.
  const bool median = texel.count >= 3;
  const Eigen::Vector3f reference =
      median ? WeightedMedian(texel) : (chosen ? chosen->colour : texel.samples[0].colour);
  const float brightest = std::max(reference.maxCoeff(), 0.0f);
  const float tolerance = median ? 0.02f + 0.15f * brightest : 0.1f + 0.5f * brightest;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  float weight = 0.0f;
  for (int i = 0; i < texel.count; ++i) {
    if ((texel.samples[i].colour - reference).cwiseAbs().maxCoeff() > tolerance) {
      ++*rejected;
      continue;
    }
    sum += texel.samples[i].weight * texel.samples[i].colour;
    weight += texel.samples[i].weight;
  }
  return weight > 0.0f ? Eigen::Vector3f(sum / weight) : reference;
}

// Samples `view` at the texels of `faces` into `samples` (indexed from `first_texel`).
void SampleView(const Mesh& mesh, const TextureView& view, std::uint32_t view_index, const GeometryMaps& maps,
                const cv::Mat& colour, const cv::Mat& confidence, const std::vector<std::uint32_t>& faces,
                const TexelLayout& layout, std::size_t first_texel, std::vector<TexelSamples>& samples,
                std::vector<std::mutex>& locks) {
  const double focal = 0.5 * (view.camera.FocalLengthX() + view.camera.FocalLengthY());
  const double depth_tolerance = 0.01 + 2.0 / focal;  // relative: 1 % plus two pixels' slope at 45 degrees
  const Eigen::Vector3d centre_in_world = view.cam_from_world.TargetOriginInSource();
  for (std::uint32_t face : faces) {
    const Mesh::Face& corners = mesh.faces[face];
    const Eigen::Vector3d& v0 = mesh.vertices[corners[0]];
    const Eigen::Vector3d& v1 = mesh.vertices[corners[1]];
    const Eigen::Vector3d& v2 = mesh.vertices[corners[2]];
    const Eigen::Vector3d normal = (v1 - v0).cross(v2 - v0).normalized();
    const auto [begin, end] = layout.face_ranges[face];
    std::lock_guard<std::mutex> lock(locks[face % locks.size()]);
    for (std::size_t t = begin; t < end; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      const Eigen::Vector3d point_in_world = (1.0 - texel.b1 - texel.b2) * v0 + double(texel.b1) * v1 + double(texel.b2) * v2;
      const Eigen::Vector3d point_in_cam = view.cam_from_world * point_in_world;
      if (!(point_in_cam.z() > 0.0)) continue;
      const Eigen::Vector2d pixel = view.camera.ImgFromCam(point_in_cam);
      const double u = pixel.x() - 0.5, v = pixel.y() - 0.5;
      if (!(u > -1.0 && v > -1.0 && u < colour.cols && v < colour.rows)) continue;
      const int col0 = static_cast<int>(std::floor(u)), row0 = static_cast<int>(std::floor(v));
      const double fu = u - col0, fv = v - row0;
      Eigen::Vector3d colour_sum = Eigen::Vector3d::Zero();
      double confidence_sum = 0.0, weight_sum = 0.0;
      for (int dr = 0; dr <= 1; ++dr) {
        for (int dc = 0; dc <= 1; ++dc) {
          const int col = col0 + dc, row = row0 + dr;
          if (col < 0 || row < 0 || col >= colour.cols || row >= colour.rows) continue;
          const double w = (dc ? fu : 1.0 - fu) * (dr ? fv : 1.0 - fv);
          const float depth = maps.depth.at<float>(row, col);
          if (w <= 0.0 || !(std::abs(depth - point_in_cam.z()) <= depth_tolerance * point_in_cam.z())) continue;
          const cv::Vec3f& value = colour.at<cv::Vec3f>(row, col);
          colour_sum += w * Eigen::Vector3d(value[0], value[1], value[2]);
          if (!confidence.empty()) {
            const cv::Vec3f& c = confidence.at<cv::Vec3f>(row, col);
            confidence_sum += w * (c[0] + c[1] + c[2]) / 3.0;
          } else {
            confidence_sum += w;
          }
          weight_sum += w;
        }
      }
      if (weight_sum < 0.5) continue;  // mostly occluded or off the image
      const double cos_angle = std::abs(normal.dot((centre_in_world - point_in_world).normalized()));
      const double resolution = (focal / point_in_cam.z()) * (focal / point_in_cam.z());
      TexelSample sample;
      sample.colour = (colour_sum / weight_sum).cast<float>();
      sample.weight = static_cast<float>(confidence_sum / weight_sum * cos_angle * resolution);
      sample.view = view_index;
      if (!(sample.weight > 0.0f) || !sample.colour.allFinite()) continue;
      samples[t - first_texel].Offer(sample);
    }
  }
}

}  // namespace

TexelBlend ParseTexelBlend(const std::string& name) {
  if (name == "fuse") return TexelBlend::kFuse;
  if (name == "single") return TexelBlend::kSingle;
  throw std::invalid_argument("unknown blend '" + name + "' (use fuse or single)");
}

TexelFusionSummary FuseTexels(const Mesh& mesh, const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                              const ViewImageSource& source, const FaceViewCandidates& candidates,
                              const std::vector<std::uint32_t>& view_of_face, const TexelLayout& layout,
                              const TexelFusionOptions& options, std::vector<cv::Mat>& pages) {
  TexelFusionSummary summary;
  summary.num_texels = layout.texels.size();
  const std::size_t texels_per_pass =
      std::max<std::size_t>(1, options.memory_limit_bytes / sizeof(TexelSamples));
  // Passes cover whole charts; a chart larger than the limit is a pass of its own.
  std::vector<std::pair<std::size_t, std::size_t>> passes;  // chart ranges
  const std::size_t num_charts = layout.chart_offsets.size() - 1;
  for (std::size_t c = 0; c < num_charts;) {
    std::size_t d = c + 1;
    while (d < num_charts && layout.chart_offsets[d + 1] - layout.chart_offsets[c] <= texels_per_pass) ++d;
    passes.emplace_back(c, d);
    c = d;
  }
  summary.num_passes = static_cast<int>(passes.size());
  std::vector<std::mutex> locks(1024);
  // The maps of the view each worker is on, reused from view to view and pass to pass.
  std::vector<GeometryMaps> worker_maps(static_cast<std::size_t>(ResolveNumThreads(options.num_threads)));
  std::size_t total_samples = 0;
  for (std::size_t p = 0; p < passes.size(); ++p) {
    const std::size_t first_texel = layout.chart_offsets[passes[p].first];
    const std::size_t end_texel = layout.chart_offsets[passes[p].second];
    // Which faces each view samples in this pass.
    std::vector<std::vector<std::uint32_t>> faces_of_view(views.size());
    for (std::size_t t = first_texel; t < end_texel;) {
      const std::uint32_t face = layout.texels[t].face;
      for (const FaceViewCandidate* c = candidates.begin(face); c != candidates.end(face); ++c) {
        faces_of_view[c->view].push_back(face);
      }
      t = layout.face_ranges[face].second;
    }
    std::vector<std::size_t> used_views;
    for (std::size_t v = 0; v < views.size(); ++v) {
      if (!faces_of_view[v].empty()) used_views.push_back(v);
    }
    summary.views_read += used_views.size();
    std::vector<TexelSamples> samples(end_texel - first_texel);
    std::optional<ProgressReporter> progress;
    if (options.show_progress) {
      progress.emplace(passes.size() > 1 ? options.progress_label + ", pass " + std::to_string(p + 1) + "/" +
                                               std::to_string(passes.size())
                                         : options.progress_label,
                       used_views.size(), "views");
    }
    ParallelForOnWorkers(used_views.size(), options.num_threads, [&](std::size_t i, int worker) {
      const std::size_t v = used_views[i];
      const cv::Mat colour = LoadViewImage(source, views, v);
      const cv::Mat confidence = LoadViewConfidence(source, views, v);
      GeometryMaps& maps = worker_maps[static_cast<std::size_t>(worker)];
      raycaster.Render(views[v], &maps);
      SampleView(mesh, views[v], static_cast<std::uint32_t>(v), maps, colour, confidence, faces_of_view[v], layout,
                 first_texel, samples, locks);
      if (progress) progress->Advance();
    });
    if (progress) progress->Finish();
    for (std::size_t t = first_texel; t < end_texel; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      cv::Vec3f& out = pages[texel.page].at<cv::Vec3f>(texel.y, texel.x);
      const TexelSamples& texel_samples = samples[t - first_texel];
      total_samples += texel_samples.count;
      if (texel_samples.count == 0) {
        out = cv::Vec3f::all(std::numeric_limits<float>::quiet_NaN());
        ++summary.texels_without_samples;
        continue;
      }
      const Eigen::Vector3f colour = Blend(texel_samples, view_of_face[texel.face], options.blend, &summary.rejected_samples);
      out = cv::Vec3f(colour.x(), colour.y(), colour.z());
    }
  }
  summary.mean_samples_per_texel = summary.num_texels ? double(total_samples) / double(summary.num_texels) : 0.0;
  return summary;
}

}  // namespace lutex
