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

void SeamCorrections::AppendAt(std::uint32_t vertex, std::vector<std::pair<std::uint32_t, Eigen::Vector3f>>* out) const {
  if (values_.empty() || vertex + 1 >= offsets_.size()) return;
  for (std::uint32_t i = offsets_[vertex]; i < offsets_[vertex + 1]; ++i) out->emplace_back(views_[i], values_[i]);
}

SeamCorrections LevelSeams(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                           const ViewRaycaster& raycaster, const ViewImageSource& source,
                           const FaceViewCandidates& candidates, const std::vector<std::uint32_t>& view_of_face,
                           const TexelFusionOptions& fusion, const SeamLevellingOptions& options,
                           SeamLevellingSummary* summary, const SeamLevellingPart* part) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  SeamLevellingSummary local;
  SeamLevellingSummary& out = summary ? *summary : local;
  out = {};
  SeamCorrections corrections;
  if (!options.enabled) return corrections;
  out.enabled = true;
  if (view_of_face.size() != mesh.faces.size()) throw std::invalid_argument("seam levelling: one view per face needed");
  if (part && part->levelled_here.size() != mesh.faces.size()) {
    throw std::invalid_argument("seam levelling: the part must say of every face whether it is levelled");
  }
  if (part && !part->shown.empty() && part->shown.size() != mesh.faces.size()) {
    throw std::invalid_argument("seam levelling: the part's shown faces must be one flag per face");
  }
  const auto here = [&](std::uint32_t f) { return !part || part->levelled_here[f]; };
  const auto shown = [&](std::uint32_t f) { return part && !part->shown.empty() && part->shown[f]; };

  // The seam points with a side here, face pair by face pair in ascending order.
  std::vector<SeamPoint> points;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      const std::uint32_t g = *n;
      if (g < f || view_of_face[g] == kNoView || view_of_face[g] == view_of_face[f] || !(here(f) || here(g))) continue;
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
  // A part with no seam of its own still shows, near its border, the corrections settled beyond it.
  if (points.empty() && !part) return corrections;

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
  if (!points.empty()) FuseTexels(mesh, views, raycaster, source, candidates, view_of_face, layout, point_fusion, pages);
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
  // Per vertex: used by a face levelled here (1), by a labelled face levelled before (2).
  std::vector<std::uint8_t> used_by(mesh.vertices.size(), 0);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView) continue;
    for (std::uint32_t v : mesh.faces[f]) used_by[v] = static_cast<std::uint8_t>(used_by[v] | (here(f) ? 1 : 2));
  }
  // Face f's correction at its vertex v is held: a face here's where the corrections reach; a face
  // before's where it meets a face here, or everywhere when it is shown (its value is then the settled one).
  const auto held = [&](std::uint32_t f, std::uint32_t v) {
    if (view_of_face[f] == kNoView) return false;
    return here(f) ? reached(v) : (used_by[v] & 1) || shown(f);
  };

  // The corrections held: (vertex, view) for the views of the faces around each vertex.
  corrections.offsets_.assign(mesh.vertices.size() + 1, 0);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (std::uint32_t v : mesh.faces[f]) corrections.offsets_[v + 1] += held(f, v);
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) corrections.offsets_[v + 1] += corrections.offsets_[v];
  {
    std::vector<std::uint32_t> fill(corrections.offsets_.begin(), corrections.offsets_.end() - 1);
    std::vector<std::uint32_t> all_views(corrections.offsets_.back());
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      for (std::uint32_t v : mesh.faces[f]) {
        if (held(f, v)) all_views[fill[v]++] = view_of_face[f];
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
  // The correction of (vertex, view), -1 when none is held (it is 0).
  const auto index = [&](std::uint32_t vertex, std::uint32_t view) {
    const auto begin = corrections.views_.begin() + corrections.offsets_[vertex];
    const auto end = corrections.views_.begin() + corrections.offsets_[vertex + 1];
    const auto found = std::lower_bound(begin, end, view);
    return found != end && *found == view ? static_cast<int>(found - corrections.views_.begin()) : -1;
  };
  // The settled ones (those a face before has) are not unknowns; the others are, in order.
  corrections.values_.assign(corrections.views_.size(), Eigen::Vector3f::Zero());
  std::vector<int> unknown(corrections.views_.size(), 0);
  if (part) {
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      if (here(f)) continue;
      for (std::uint32_t v : mesh.faces[f]) {
        const int c = held(f, v) ? index(v, view_of_face[f]) : -1;
        if (c < 0 || unknown[c] < 0) continue;
        unknown[c] = -1;
        corrections.values_[c] = part->settled(v, view_of_face[f]);
      }
    }
  }
  std::size_t n = 0;
  for (int& u : unknown) u = u < 0 ? -1 : static_cast<int>(n++);
  const auto unknown_of = [&](int c) { return c < 0 ? -1 : unknown[c]; };
  const auto value_of = [&](int c) { return c < 0 ? Eigen::Vector3f::Zero().eval() : corrections.values_[c]; };

  // The seam points seen from both sides, and the step between their colours.
  std::vector<std::array<int, 4>> point_corrections;
  std::vector<Eigen::Vector3d> point_step;  // c_b - c_a
  std::vector<float> point_t;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SeamPoint& point = points[i];
    const Eigen::Vector3d step = colour_of(2 * i + 1) - colour_of(2 * i);
    if (!step.allFinite()) continue;
    const std::uint32_t a = view_of_face[point.face_a], b = view_of_face[point.face_b];
    point_corrections.push_back({index(point.p, a), index(point.q, a), index(point.p, b), index(point.q, b)});
    point_step.push_back(step);
    point_t.push_back(point.t);
  }
  points = {};
  texel_of_entry = {};
  pages = {};
  layout = {};
  out.num_unknowns = n;
  out.num_seam_points = point_step.size();
  if (point_step.empty()) return part ? corrections : SeamCorrections();
  // What each point's step is after the corrections (mean over channels of the absolute value); before
  // any, with `corrected` false.
  const auto remaining_step = [&](std::size_t i, bool corrected) {
    const float t = point_t[i];
    const std::array<int, 4>& c = point_corrections[i];
    const Eigen::Vector3f change =
        !corrected ? Eigen::Vector3f::Zero()
                   : Eigen::Vector3f((1.0f - t) * value_of(c[0]) + t * value_of(c[1]) - (1.0f - t) * value_of(c[2]) -
                                     t * value_of(c[3]));
    return (point_step[i] - change.cast<double>()).cwiseAbs().mean();
  };
  std::vector<double> residuals(point_step.size());
  for (std::size_t i = 0; i < residuals.size(); ++i) residuals[i] = remaining_step(i, false);
  for (double r : residuals) out.step_before += r / double(residuals.size());
  // Robust scale: the steps' median absolute value (as a standard deviation), but no less than a step no
  // one can see (about one 8-bit sRGB level in mid-tones, in linear albedo).
  std::vector<double> sorted = residuals;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double scale = std::max(1.4826 * sorted[sorted.size() / 2], kInvisibleStep);
  sorted = {};

  // The normal equations (seam_levelling_system.h) in the unknowns: the chart edges of the faces here
  // once (an edge to a settled correction pulls towards its value), the seam points each round (their
  // steps less what the settled corrections already change).
  SeamLevellingSystem system(n, options.fade, options.smoothness);
  ChannelVectors edge_rhs = ChannelVectors::Zero(static_cast<Eigen::Index>(n), 3);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (view_of_face[f] == kNoView || !here(f)) continue;
    const Mesh::Face& face = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int ci = index(face[k], view_of_face[f]), cj = index(face[(k + 1) % 3], view_of_face[f]);
      const int i = unknown_of(ci), j = unknown_of(cj);
      system.AddEdge(i, j);
      if (i >= 0 && j < 0) edge_rhs.row(i) += options.smoothness * value_of(cj).cast<double>().transpose();
      if (j >= 0 && i < 0) edge_rhs.row(j) += options.smoothness * value_of(ci).cast<double>().transpose();
    }
  }
  system.FinishEdges();
  // Iteratively reweighted least squares with Cauchy weights on the seam points: a step that texture
  // detail, a particle or a misregistration makes at one point is not spread into the charts.
  ChannelVectors rhs(static_cast<Eigen::Index>(n), 3), solution;
  for (int round = 0; round < kRobustRounds; ++round) {
    system.ClearPoints();
    rhs = edge_rhs;
    for (std::size_t i = 0; i < point_step.size(); ++i) {
      const double weight = 1.0 / (1.0 + (residuals[i] / scale) * (residuals[i] / scale));
      const std::array<double, 4> coefficients = SeamPointCoefficients(point_t[i]);
      std::array<int, 4> unknowns;
      Eigen::RowVector3d step = point_step[i].transpose();
      for (int r = 0; r < 4; ++r) {
        unknowns[r] = unknown_of(point_corrections[i][r]);
        if (unknowns[r] < 0) step -= coefficients[r] * value_of(point_corrections[i][r]).cast<double>().transpose();
      }
      system.AddPoint(unknowns, point_t[i], weight);
      for (int r = 0; r < 4; ++r) {
        if (unknowns[r] >= 0) rhs.row(unknowns[r]) += weight * coefficients[r] * step;
      }
    }
    out.iterations = std::max(out.iterations, system.Solve(rhs, options.max_iterations, kTolerance, &solution));
    for (std::size_t c = 0; c < unknown.size(); ++c) {
      if (unknown[c] >= 0) corrections.values_[c] = solution.row(Eigen::Index(unknown[c])).transpose().cast<float>();
    }
    for (std::size_t i = 0; i < residuals.size(); ++i) residuals[i] = remaining_step(i, true);
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
