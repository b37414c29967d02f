#include "texturing/seam_levelling.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>


#include "lib/util/parallel_for.h"
#include "texturing/seam_levelling_system.h"
#include "texturing/view_selection.h"

namespace lutex {

namespace {

constexpr std::array<float, 3> kEdgePositions{0.25f, 0.5f, 0.75f};
constexpr double kInvisibleStep = 0.002;
constexpr int kRobustRounds = 3;
constexpr double kFadeLengths = 4.0;
// Conjugate gradients stop at |residual| <= this x |right-hand side|.
constexpr double kTolerance = 1e-5;
// Seam points fused per pseudo-page (the fusion writes into pages; these are 4096 wide).
constexpr int kPageSide = 4096;

// A point of a seam edge (p, q) at p + t (q - p), seen through face_a (view a) and face_b (view b).
struct SeamPoint {
  std::uint32_t face_a = 0, face_b = 0;
  std::uint32_t p = 0, q = 0;
  float t = 0.0f;
};

// Barycentric (b1, b2) in `face` of the point (1 - t) p + t q of its edge.
std::pair<float, float> EdgeBarycentrics(const Mesh::Face& face, std::uint32_t p, std::uint32_t q, float t) {
  std::array<float, 3> b{0.0f, 0.0f, 0.0f};
  for (int k = 0; k < 3; ++k) {
    if (face[k] == p) b[k] = 1.0f - t;
    if (face[k] == q) b[k] = t;
  }
  return {b[1], b[2]};
}

}  // namespace

void SeamLevellingOptions::Check() const {
  if (!(smoothness > 0.0 && std::isfinite(smoothness))) throw std::invalid_argument("seam levelling: smoothness must be positive");
  if (!(fade >= 0.0 && std::isfinite(fade))) throw std::invalid_argument("seam levelling: fade must be >= 0");
  if (max_iterations < 1) throw std::invalid_argument("seam levelling: at least one iteration");
}

std::string DescribeSeamLevelling(const SeamLevellingSummary& summary) {
  if (!summary.enabled) return "off";
  if (summary.num_seam_points == 0) return "no seams";
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << "colour step at " << summary.num_seam_points << " seam points "
       << 100.0 * summary.step_before << " % -> " << 100.0 * summary.step_after << " % of full scale ("
       << summary.num_unknowns << " vertex-image corrections, " << summary.iterations << " iterations, "
       << std::setprecision(1) << summary.seconds << " s)";
  return text.str();
}

Eigen::Vector3f SeamCorrections::At(std::uint32_t vertex, std::uint32_t view) const {
  if (values_.empty() || vertex + 1 >= offsets_.size()) return Eigen::Vector3f::Zero();
  const auto begin = views_.begin() + offsets_[vertex], end = views_.begin() + offsets_[vertex + 1];
  const auto found = std::lower_bound(begin, end, view);
  if (found == end || *found != view) return Eigen::Vector3f::Zero();
  return values_[static_cast<std::size_t>(found - views_.begin())];
}

SeamCorrections LevelSeams(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                           const ViewRaycaster& raycaster, const ViewImageSource& source,
                           const FaceViewCandidates& candidates, const std::vector<std::uint32_t>& view_of_face,
                           const TexelFusionOptions& fusion, const SeamLevellingOptions& options,
                           SeamLevellingSummary* summary) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  SeamLevellingSummary local;
  SeamLevellingSummary& out = summary ? *summary : local;
  out = {};
  SeamCorrections corrections;
  if (!options.enabled) return corrections;
  out.enabled = true;
  if (view_of_face.size() != mesh.faces.size()) throw std::invalid_argument("seam levelling: one view per face needed");

  // The seam points, face pair by face pair in ascending order.
  std::vector<SeamPoint> points;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      const std::uint32_t g = *n;
      if (g < f || view_of_face[g] == kNoView || view_of_face[g] == view_of_face[f]) continue;
      std::array<std::uint32_t, 2> shared{};
      int num_shared = 0;
      for (std::uint32_t v : mesh.faces[f]) {
        const auto& other = mesh.faces[g];
        if (num_shared < 2 && std::find(other.begin(), other.end(), v) != other.end()) shared[num_shared++] = v;
      }
      if (num_shared < 2) continue;
      for (float t : kEdgePositions) points.push_back({f, g, shared[0], shared[1], t});
    }
  }
  if (points.empty()) return corrections;

  // Their colours through each side's face: a texel layout of two texels per point, face by face.
  const std::size_t num_entries = 2 * points.size();
  std::vector<std::size_t> face_count(mesh.faces.size() + 1, 0);
  for (const SeamPoint& point : points) {
    ++face_count[point.face_a + 1];
    ++face_count[point.face_b + 1];
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) face_count[f + 1] += face_count[f];
  TexelLayout layout;
  layout.texels.resize(num_entries);
  layout.face_ranges.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) layout.face_ranges[f] = {face_count[f], face_count[f]};
  std::vector<std::size_t> texel_of_entry(num_entries);  // entry 2i: side a of point i, 2i + 1: side b
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SeamPoint& point = points[i];
    for (int side = 0; side < 2; ++side) {
      const std::uint32_t face = side == 0 ? point.face_a : point.face_b;
      const std::size_t t = layout.face_ranges[face].second++;
      const auto [b1, b2] = EdgeBarycentrics(mesh.faces[face], point.p, point.q, point.t);
      AtlasTexel& texel = layout.texels[t];
      texel.face = face;
      texel.page = static_cast<std::uint16_t>(t / (std::size_t(kPageSide) * kPageSide));
      texel.x = static_cast<std::uint16_t>(t % kPageSide);
      texel.y = static_cast<std::uint16_t>((t / kPageSide) % kPageSide);
      texel.b1 = b1;
      texel.b2 = b2;
      texel_of_entry[2 * i + side] = t;
    }
  }
  face_count.clear();
  face_count.shrink_to_fit();
  // Groups of whole faces, so that the fusion can split its passes between them.
  layout.chart_offsets.push_back(0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::size_t end = layout.face_ranges[f].second;
    if (end - layout.chart_offsets.back() >= std::size_t(kPageSide)) layout.chart_offsets.push_back(end);
  }
  if (layout.chart_offsets.back() != num_entries) layout.chart_offsets.push_back(num_entries);
  std::vector<cv::Mat> pages;
  for (std::size_t first = 0; first < num_entries; first += std::size_t(kPageSide) * kPageSide) {
    const std::size_t rows = std::min<std::size_t>(kPageSide, (num_entries - first + kPageSide - 1) / kPageSide);
    pages.emplace_back(static_cast<int>(rows), kPageSide, CV_32FC3, cv::Scalar::all(0));
  }
  TexelFusionOptions point_fusion = fusion;
  point_fusion.progress_label = "texture: seam levelling";
  FuseTexels(mesh, views, raycaster, source, candidates, view_of_face, layout, point_fusion, pages);
  const auto colour_of = [&](std::size_t entry) {
    const AtlasTexel& texel = layout.texels[texel_of_entry[entry]];
    const cv::Vec3f& c = pages[texel.page].at<cv::Vec3f>(texel.y, texel.x);
    return Eigen::Vector3d(c[0], c[1], c[2]);
  };

  // The vertices a correction reaches: within kFadeLengths fade lengths, sqrt(smoothness / fade) edges, of
  // a seam (beyond, it would be below e^-kFadeLengths of the seam's; it is 0 there). All with fade 0.
  const std::uint8_t reach =
      options.fade > 0.0
          ? static_cast<std::uint8_t>(std::min(250.0, std::ceil(kFadeLengths * std::sqrt(options.smoothness / options.fade))))
          : std::uint8_t{254};
  std::vector<std::uint8_t> ring(mesh.vertices.size(), 255);
  for (const SeamPoint& point : points) ring[point.p] = ring[point.q] = 0;
  for (std::uint8_t r = 1; r <= reach && options.fade > 0.0; ++r) {
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      if (view_of_face[f] == kNoView) continue;
      const Mesh::Face& face = mesh.faces[f];
      if (std::min({ring[face[0]], ring[face[1]], ring[face[2]]}) != r - 1) continue;
      for (std::uint32_t v : face) ring[v] = std::min(ring[v], r);
    }
  }
  const auto reached = [&](std::uint32_t v) { return options.fade == 0.0 || ring[v] <= reach; };

  // The unknowns: (vertex, view) for the views of the faces around each vertex reached.
  corrections.offsets_.assign(mesh.vertices.size() + 1, 0);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    for (std::uint32_t v : mesh.faces[f]) corrections.offsets_[v + 1] += reached(v);
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) corrections.offsets_[v + 1] += corrections.offsets_[v];
  {
    std::vector<std::uint32_t> fill(corrections.offsets_.begin(), corrections.offsets_.end() - 1);
    std::vector<std::uint32_t> all_views(corrections.offsets_.back());
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      if (view_of_face[f] == kNoView) continue;
      for (std::uint32_t v : mesh.faces[f]) {
        if (reached(v)) all_views[fill[v]++] = view_of_face[f];
      }
    }
    // Distinct views per vertex, compacted in place of the counts.
    std::uint32_t kept = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const auto begin = all_views.begin() + corrections.offsets_[v], end = all_views.begin() + corrections.offsets_[v + 1];
      std::sort(begin, end);
      const auto unique_end = std::unique(begin, end);
      corrections.offsets_[v] = kept;
      for (auto it = begin; it != unique_end; ++it) all_views[kept++] = *it;
    }
    corrections.offsets_.back() = kept;
    all_views.resize(kept);
    corrections.views_ = std::move(all_views);
  }
  const std::size_t n = corrections.views_.size();
  // The unknown of (vertex, view), -1 for a vertex the corrections do not reach.
  const auto index = [&](std::uint32_t vertex, std::uint32_t view) {
    if (!reached(vertex)) return -1;
    const auto begin = corrections.views_.begin() + corrections.offsets_[vertex];
    const auto end = corrections.views_.begin() + corrections.offsets_[vertex + 1];
    return static_cast<int>(std::lower_bound(begin, end, view) - corrections.views_.begin());
  };

  // The seam points seen from both sides, and the step between their colours.
  std::vector<std::array<int, 4>> point_unknowns;
  std::vector<Eigen::Vector3d> point_step;  // c_b - c_a
  std::vector<float> point_t;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SeamPoint& point = points[i];
    const Eigen::Vector3d step = colour_of(2 * i + 1) - colour_of(2 * i);
    if (!step.allFinite()) continue;
    const std::uint32_t a = view_of_face[point.face_a], b = view_of_face[point.face_b];
    point_unknowns.push_back({index(point.p, a), index(point.q, a), index(point.p, b), index(point.q, b)});
    point_step.push_back(step);
    point_t.push_back(point.t);
  }
  points = {};
  texel_of_entry = {};
  pages = {};
  layout = {};
  out.num_unknowns = n;
  out.num_seam_points = point_step.size();
  if (point_step.empty()) return {};
  // What each point's step is after corrections `g` (mean over channels of the absolute value).
  const auto remaining_step = [&](std::size_t i, const std::vector<Eigen::Vector3f>& g) {
    const float t = point_t[i];
    const std::array<int, 4>& u = point_unknowns[i];
    const Eigen::Vector3f change =
        g.empty() ? Eigen::Vector3f::Zero()
                  : Eigen::Vector3f((1.0f - t) * g[u[0]] + t * g[u[1]] - (1.0f - t) * g[u[2]] - t * g[u[3]]);
    return (point_step[i] - change.cast<double>()).cwiseAbs().mean();
  };
  std::vector<double> residuals(point_step.size());
  for (std::size_t i = 0; i < residuals.size(); ++i) residuals[i] = remaining_step(i, {});
  for (double r : residuals) out.step_before += r / double(residuals.size());
  // Robust scale: the steps' median absolute value (as a standard deviation), but no less than a step no
  // one can see (about one 8-bit sRGB level in mid-tones, in linear albedo).
  std::vector<double> sorted = residuals;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double scale = std::max(1.4826 * sorted[sorted.size() / 2], kInvisibleStep);
  sorted = {};

  // The normal equations (seam_levelling_system.h): the chart edges once, the seam points each round.
  SeamLevellingSystem system(n, options.fade, options.smoothness);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    const Mesh::Face& face = mesh.faces[f];
    for (int k = 0; k < 3; ++k) system.AddEdge(index(face[k], view_of_face[f]), index(face[(k + 1) % 3], view_of_face[f]));
  }
  system.FinishEdges();
  // Iteratively reweighted least squares with Cauchy weights on the seam points: a step that texture
  // detail, a particle or a misregistration makes at one point is not spread into the charts.
  ChannelVectors rhs(static_cast<Eigen::Index>(n), 3), solution;
  for (int round = 0; round < kRobustRounds; ++round) {
    system.ClearPoints();
    rhs.setZero();
    for (std::size_t i = 0; i < point_step.size(); ++i) {
      const double weight = 1.0 / (1.0 + (residuals[i] / scale) * (residuals[i] / scale));
      const std::array<double, 4> coefficients = SeamPointCoefficients(point_t[i]);
      system.AddPoint(point_unknowns[i], point_t[i], weight);
      for (int r = 0; r < 4; ++r) rhs.row(point_unknowns[i][r]) += weight * coefficients[r] * point_step[i].transpose();
    }
    out.iterations = std::max(out.iterations, system.Solve(rhs, options.max_iterations, kTolerance, &solution));
    corrections.values_.resize(n);
    for (std::size_t u = 0; u < n; ++u) corrections.values_[u] = solution.row(Eigen::Index(u)).transpose().cast<float>();
    for (std::size_t i = 0; i < residuals.size(); ++i) residuals[i] = remaining_step(i, corrections.values_);
  }
  for (double r : residuals) out.step_after += r / double(residuals.size());

  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return corrections;
}

void ApplySeamCorrections(const Mesh& mesh, const std::vector<std::uint32_t>& view_of_face,
                          const SeamCorrections& corrections, const std::vector<std::uint32_t>& source_vertex,
                          const TexelLayout& layout, int num_threads, std::vector<cv::Mat>& pages) {
  if (corrections.empty()) return;
  ParallelFor(mesh.faces.size(), num_threads, [&](std::size_t f) {
    const auto [begin, end] = layout.face_ranges[f];
    if (begin == end) return;
    std::array<Eigen::Vector3f, 3> corner;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.faces[f][k];
      corner[k] = corrections.At(source_vertex.empty() ? v : source_vertex[v], view_of_face[f]);
    }
    for (std::size_t t = begin; t < end; ++t) {
      const AtlasTexel& texel = layout.texels[t];
      const Eigen::Vector3f change = (1.0f - texel.b1 - texel.b2) * corner[0] + texel.b1 * corner[1] + texel.b2 * corner[2];
      cv::Vec3f& colour = pages[texel.page].at<cv::Vec3f>(texel.y, texel.x);
      if (std::isnan(colour[0])) continue;  // unseen: filled from its neighbours later
      for (int c = 0; c < 3; ++c) colour[c] = std::max(0.0f, colour[c] + change[c]);
    }
  });
}

}  // namespace lutex
