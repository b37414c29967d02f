#include "texturing/texel_fusion.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "lib/geometry/spatial_batches.h"
#include "lib/util/chunked_array.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"
#include "texturing/view_pixel_depths.h"

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

// A face a pass samples, and where its texels' samples start in the pass's buffer.
struct PassFace {
  std::uint32_t face = 0;
  std::size_t first_sample = 0;
};

// The pixels of `view` that sampling `faces` can read: the bounding box of their corners' projections,
// with a margin for the bilinear footprint and for a distortion that bows an edge outwards. The whole
// image when a corner is behind the camera.
cv::Rect SampledWindow(const Mesh& mesh, const TextureView& view, const std::vector<PassFace>& faces) {
  constexpr double kMargin = 4.0;
  const cv::Rect image(0, 0, static_cast<int>(view.camera.width), static_cast<int>(view.camera.height));
  double min_u = std::numeric_limits<double>::infinity(), min_v = min_u;
  double max_u = -min_u, max_v = -min_u;
  for (const PassFace& pass_face : faces) {
    for (const std::uint32_t vertex : mesh.faces[pass_face.face]) {
      const Eigen::Vector3d point_in_cam = view.cam_from_world * mesh.vertices[vertex];
      if (!(point_in_cam.z() > 0.0)) return image;
      const Eigen::Vector2d pixel = view.camera.ImgFromCam(point_in_cam);
      if (!pixel.allFinite()) return image;
      min_u = std::min(min_u, pixel.x());
      max_u = std::max(max_u, pixel.x());
      min_v = std::min(min_v, pixel.y());
      max_v = std::max(max_v, pixel.y());
    }
  }
  if (!(max_u >= min_u)) return cv::Rect();
  const auto clamp = [](double value, int high) { return static_cast<int>(std::clamp(value, 0.0, double(high))); };
  const int col0 = clamp(std::floor(min_u - kMargin), image.width), row0 = clamp(std::floor(min_v - kMargin), image.height);
  const int col1 = clamp(std::ceil(max_u + kMargin), image.width), row1 = clamp(std::ceil(max_v + kMargin), image.height);
  return cv::Rect(col0, row0, col1 - col0, row1 - row0);
}

// Where a texel falls in a view: its surface point, the point in the camera frame, and the top-left pixel
// of its bilinear footprint with the fractions towards the next column and row.
struct TexelInView {
  Eigen::Vector3d point_in_world, point_in_cam;
  int col0 = 0, row0 = 0;
  double fu = 0.0, fv = 0.0;
};

// False when the texel is behind the camera or its footprint is off the image.
bool ProjectTexel(const TextureView& view, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                  const Eigen::Vector3d& v2, const AtlasTexel& texel, TexelInView* out) {
  out->point_in_world = (1.0 - texel.b1 - texel.b2) * v0 + double(texel.b1) * v1 + double(texel.b2) * v2;
  out->point_in_cam = view.cam_from_world * out->point_in_world;
  if (!(out->point_in_cam.z() > 0.0)) return false;
  const Eigen::Vector2d pixel = view.camera.ImgFromCam(out->point_in_cam);
  const double u = pixel.x() - 0.5, v = pixel.y() - 0.5;
  if (!(u > -1.0 && v > -1.0 && u < double(view.camera.width) && v < double(view.camera.height))) return false;
  out->col0 = static_cast<int>(std::floor(u));
  out->row0 = static_cast<int>(std::floor(v));
  out->fu = u - out->col0;
  out->fv = v - out->row0;
  return true;
}

// The pixels whose depth sampling `faces` in `view` reads (with repeats).
std::vector<cv::Point> SampledPixels(const Mesh& mesh, const TextureView& view, const std::vector<PassFace>& faces,
                                     const TexelLayout& layout) {
  std::vector<cv::Point> pixels;
  for (const PassFace& pass_face : faces) {
    const Mesh::Face& corners = mesh.faces[pass_face.face];
    const auto [begin, end] = layout.face_ranges[pass_face.face];
    for (std::size_t t = begin; t < end; ++t) {
      TexelInView at;
      if (!ProjectTexel(view, mesh.vertices[corners[0]], mesh.vertices[corners[1]], mesh.vertices[corners[2]],
                        layout.texels[t], &at)) {
        continue;
      }
      for (int dr = 0; dr <= 1; ++dr) {
        for (int dc = 0; dc <= 1; ++dc) pixels.emplace_back(at.col0 + dc, at.row0 + dr);
      }
    }
  }
  return pixels;
}

// Samples `view` at the texels of `faces` into `samples`. `colour` and `confidence` (empty: every pixel
// trusted) are the pixels of `window`; `depths` must have the pixels the texels' footprints read.
void SampleView(const Mesh& mesh, const TextureView& view, std::uint32_t view_index, const ViewPixelDepths& depths,
                const cv::Rect& window, const cv::Mat& colour, const cv::Mat& confidence, const std::vector<PassFace>& faces,
                const TexelLayout& layout, ChunkedArray<TexelSamples>& samples, std::vector<std::mutex>& locks) {
  const double focal = 0.5 * (view.camera.FocalLengthX() + view.camera.FocalLengthY());
  const double depth_tolerance = 0.01 + 2.0 / focal;  // relative: 1 % plus two pixels' slope at 45 degrees
  const Eigen::Vector3d centre_in_world = view.cam_from_world.TargetOriginInSource();
  for (const auto& [face, first_sample] : faces) {
    const Mesh::Face& corners = mesh.faces[face];
    const Eigen::Vector3d& v0 = mesh.vertices[corners[0]];
    const Eigen::Vector3d& v1 = mesh.vertices[corners[1]];
    const Eigen::Vector3d& v2 = mesh.vertices[corners[2]];
    const Eigen::Vector3d normal = (v1 - v0).cross(v2 - v0).normalized();
    const auto [begin, end] = layout.face_ranges[face];
    std::lock_guard<std::mutex> lock(locks[face % locks.size()]);
    for (std::size_t t = begin; t < end; ++t) {
      TexelInView at;
      if (!ProjectTexel(view, v0, v1, v2, layout.texels[t], &at)) continue;
      const Eigen::Vector3d& point_in_cam = at.point_in_cam;
      Eigen::Vector3d colour_sum = Eigen::Vector3d::Zero();
      double confidence_sum = 0.0, weight_sum = 0.0;
      for (int dr = 0; dr <= 1; ++dr) {
        for (int dc = 0; dc <= 1; ++dc) {
          const int col = at.col0 + dc, row = at.row0 + dr;
          const int window_col = col - window.x, window_row = row - window.y;
          if (window_col < 0 || window_row < 0 || window_col >= colour.cols || window_row >= colour.rows) continue;
          float depth = 0.0f;
          if (!depths.At(col, row, &depth)) continue;
          const double w = (dc ? at.fu : 1.0 - at.fu) * (dr ? at.fv : 1.0 - at.fv);
          if (w <= 0.0 || !(std::abs(depth - point_in_cam.z()) <= depth_tolerance * point_in_cam.z())) continue;
          const cv::Vec3f& value = colour.at<cv::Vec3f>(window_row, window_col);
          colour_sum += w * Eigen::Vector3d(value[0], value[1], value[2]);
          if (!confidence.empty()) {
            const cv::Vec3f& c = confidence.at<cv::Vec3f>(window_row, window_col);
            confidence_sum += w * (c[0] + c[1] + c[2]) / 3.0;
          } else {
            confidence_sum += w;
          }
          weight_sum += w;
        }
      }
      if (weight_sum < 0.5) continue;  // mostly occluded or off the image
      const double cos_angle = std::abs(normal.dot((centre_in_world - at.point_in_world).normalized()));
      const double resolution = (focal / point_in_cam.z()) * (focal / point_in_cam.z());
      TexelSample sample;
      sample.colour = (colour_sum / weight_sum).cast<float>();
      sample.weight = static_cast<float>(confidence_sum / weight_sum * cos_angle * resolution);
      sample.view = view_index;
      if (!(sample.weight > 0.0f) || !sample.colour.allFinite()) continue;
      samples[first_sample + (t - begin)].Offer(sample);
    }
  }
}

// Whether to cast only the pixels the texels of `faces` read instead of rendering `window`: when they
// are a small part of it. A pixel cast alone costs about as much as kRenderedPerCast pixels rendered
// adaptively (raycast_benchmark: a quarter of the pixels cast in packets, the rest filled).
bool CastPixelsAlone(const TexelLayout& layout, const std::vector<PassFace>& faces, const cv::Rect& window) {
  constexpr double kRenderedPerCast = 16.0;
  std::size_t texels = 0;
  for (const PassFace& pass_face : faces) {
    texels += layout.face_ranges[pass_face.face].second - layout.face_ranges[pass_face.face].first;
  }
  return 4.0 * double(texels) * kRenderedPerCast < double(window.area());
}

// The charts of each pass over the views, at most `texels_per_pass` texels each, batched along the
// surface (spatial_batches.h) by their texel-weighted centroids: a pass reads only the views that see
// its part of the surface, and casts only the part of each view that shows it (SampledWindow).
std::vector<std::vector<std::size_t>> PlanPasses(const Mesh& mesh, const TexelLayout& layout,
                                                 std::size_t texels_per_pass) {
  const std::size_t num_charts = layout.chart_offsets.size() - 1;
  Eigen::AlignedBox3d bounds;
  if (layout.texels.size() > texels_per_pass) {
    for (const Eigen::Vector3d& vertex : mesh.vertices) bounds.extend(vertex);
  }
  std::vector<Eigen::Vector3d> centroids(num_charts, bounds.isEmpty() ? Eigen::Vector3d::Zero() : bounds.min());
  std::vector<std::size_t> sizes(num_charts);
  for (std::size_t c = 0; c < num_charts; ++c) {
    sizes[c] = layout.chart_offsets[c + 1] - layout.chart_offsets[c];
    if (bounds.isEmpty() || sizes[c] == 0) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t t = layout.chart_offsets[c]; t < layout.chart_offsets[c + 1];) {
      const std::uint32_t face = layout.texels[t].face;
      const std::size_t end = layout.face_ranges[face].second;
      for (const std::uint32_t vertex : mesh.faces[face]) sum += double(end - t) * mesh.vertices[vertex];
      t = end;
    }
    centroids[c] = sum / double(3 * sizes[c]);
  }
  return BatchAlongMortonCurve(centroids, sizes, bounds, texels_per_pass);
}

}  // namespace

void TexelFusionSummary::Add(const TexelFusionSummary& other) {
  const std::size_t texels = num_texels + other.num_texels;
  mean_samples_per_texel =
      texels ? (mean_samples_per_texel * double(num_texels) + other.mean_samples_per_texel * double(other.num_texels)) /
                   double(texels)
             : 0.0;
  num_passes += other.num_passes;
  views_read += other.views_read;
  views_cast_by_pixel += other.views_cast_by_pixel;
  num_texels = texels;
  texels_without_samples += other.texels_without_samples;
  rejected_samples += other.rejected_samples;
}

std::size_t FusionBytesPerTexel() { return sizeof(TexelSamples); }

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
      std::max<std::size_t>(1, options.memory_limit_bytes / FusionBytesPerTexel());
  const std::vector<std::vector<std::size_t>> passes = PlanPasses(mesh, layout, texels_per_pass);
  summary.num_passes = static_cast<int>(passes.size());
  std::vector<std::mutex> locks(1024);
  // The maps of the view each worker is on, reused from view to view and pass to pass.
  std::vector<GeometryMaps> worker_maps(static_cast<std::size_t>(ResolveNumThreads(options.num_threads)));
  std::size_t total_samples = 0;
  for (std::size_t p = 0; p < passes.size(); ++p) {
    // Which faces each view samples in this pass, and where each face's samples go.
    std::vector<std::vector<PassFace>> faces_of_view(views.size());
    // The pass's charts in buffer order: their texels [begin, end) and where their samples start.
    struct PassChart {
      std::size_t begin = 0, end = 0, first_sample = 0;
    };
    std::vector<PassChart> pass_charts;
    std::size_t num_samples = 0;
    for (const std::size_t chart : passes[p]) {
      const std::size_t chart_begin = layout.chart_offsets[chart], chart_end = layout.chart_offsets[chart + 1];
      pass_charts.push_back({chart_begin, chart_end, num_samples});
      for (std::size_t t = chart_begin; t < chart_end;) {
        const std::uint32_t face = layout.texels[t].face;
        const std::uint32_t* face_views = candidates.Views(face);
        for (std::size_t c = 0; c < candidates.NumViews(face); ++c) {
          faces_of_view[face_views[c]].push_back({face, num_samples + (t - chart_begin)});
        }
        t = layout.face_ranges[face].second;
      }
      num_samples += chart_end - chart_begin;
    }
    std::vector<std::size_t> used_views;
    for (std::size_t v = 0; v < views.size(); ++v) {
      if (!faces_of_view[v].empty()) used_views.push_back(v);
    }
    // Views held in memory first (the order does not change the result: TexelSamples::Offer).
    if (source.is_held) {
      std::stable_partition(used_views.begin(), used_views.end(), [&](std::size_t v) { return source.is_held(v); });
    }
    ChunkedArray<TexelSamples> samples(num_samples);
    std::atomic<std::size_t> views_outside{0};  // whose faces all project outside the image: not read
    std::atomic<std::size_t> views_cast_by_pixel{0};
    std::optional<ProgressReporter> progress;
    if (options.show_progress) {
      progress.emplace(passes.size() > 1 ? options.progress_label + ", pass " + std::to_string(p + 1) + "/" +
                                               std::to_string(passes.size())
                                         : options.progress_label,
                       used_views.size(), "views");
    }
    ParallelForOnWorkers(used_views.size(), options.num_threads, [&](std::size_t i, int worker) {
      const std::size_t v = used_views[i];
      // Only the rectangle the pass's faces project to is read and linearised; it is ray cast, or only
      // the pixels the texels read when they are few in it (seam points).
      const cv::Rect window = SampledWindow(mesh, views[v], faces_of_view[v]);
      if (window.empty()) {  // the faces project outside the image
        ++views_outside;
        if (progress) progress->Advance();
        return;
      }
      const cv::Mat colour = LoadViewImage(source, views, v, window);
      const cv::Mat confidence = LoadViewConfidence(source, views, v, window);
      if (CastPixelsAlone(layout, faces_of_view[v], window)) {
        ++views_cast_by_pixel;
        const ViewPixelDepths depths(raycaster, views[v], SampledPixels(mesh, views[v], faces_of_view[v], layout));
        SampleView(mesh, views[v], static_cast<std::uint32_t>(v), depths, window, colour, confidence,
                   faces_of_view[v], layout, samples, locks);
      } else {
        GeometryMaps& maps = worker_maps[static_cast<std::size_t>(worker)];
        raycaster.Render(views[v], &maps, window);
        SampleView(mesh, views[v], static_cast<std::uint32_t>(v), ViewPixelDepths(maps), window, colour, confidence,
                   faces_of_view[v], layout, samples, locks);
      }
      if (progress) progress->Advance();
    });
    if (progress) progress->Finish();
    summary.views_read += used_views.size() - views_outside.load();
    summary.views_cast_by_pixel += views_cast_by_pixel.load();
    // Each chart's texels blended on their own (they write their own texels), counted per chart and
    // summed in order.
    struct ChartCounts {
      std::size_t samples = 0, without_samples = 0, rejected = 0;
    };
    std::vector<ChartCounts> counts(pass_charts.size());
    ParallelFor(pass_charts.size(), options.num_threads, [&](std::size_t r) {
      ChartCounts& count = counts[r];
      std::size_t s = pass_charts[r].first_sample;
      for (std::size_t t = pass_charts[r].begin; t < pass_charts[r].end; ++t, ++s) {
        const AtlasTexel& texel = layout.texels[t];
        cv::Vec3f& out = pages[texel.page].at<cv::Vec3f>(texel.y, texel.x);
        const TexelSamples& texel_samples = samples[s];
        count.samples += texel_samples.count;
        if (texel_samples.count == 0) {
          out = cv::Vec3f::all(std::numeric_limits<float>::quiet_NaN());
          ++count.without_samples;
          continue;
        }
        const Eigen::Vector3f colour = Blend(texel_samples, view_of_face[texel.face], options.blend, &count.rejected);
        out = cv::Vec3f(colour.x(), colour.y(), colour.z());
      }
    });
    for (const ChartCounts& count : counts) {
      total_samples += count.samples;
      summary.texels_without_samples += count.without_samples;
      summary.rejected_samples += count.rejected;
    }
  }
  summary.mean_samples_per_texel = summary.num_texels ? double(total_samples) / double(summary.num_texels) : 0.0;
  return summary;
}

}  // namespace lutex
