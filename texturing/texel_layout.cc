#include "texturing/texel_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/util/parallel_for.h"

namespace lutex {

namespace {

struct TexelOwner {
  int face_index = -1;  // into chart.faces
  float distance = std::numeric_limits<float>::infinity();
  float b1 = 0.0f, b2 = 0.0f;
};

// Closest point of segment (a, b) to q: squared distance and the parameter t along it.
std::pair<double, double> ClosestOnSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q) {
  const Eigen::Vector2d ab = b - a;
  const double length_squared = ab.squaredNorm();
  const double t = length_squared > 0.0 ? std::clamp((q - a).dot(ab) / length_squared, 0.0, 1.0) : 0.0;
  return {(a + t * ab - q).squaredNorm(), t};
}

// Which face of the chart, and which point of it, each texel of the chart's rectangle shows (row-major;
// face_index -1: none).
std::vector<TexelOwner> FindTexelOwners(const TextureChart& chart, double gutter) {
  std::vector<TexelOwner> owners(static_cast<std::size_t>(chart.width) * chart.height);
  for (std::size_t i = 0; i < chart.faces.size(); ++i) {
    const Eigen::Vector2d p[3] = {chart.corner_texels[3 * i].cast<double>(), chart.corner_texels[3 * i + 1].cast<double>(),
                                  chart.corner_texels[3 * i + 2].cast<double>()};
    const double area2 = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
    const double x_low = std::min({p[0].x(), p[1].x(), p[2].x()}) - gutter;
    const double x_high = std::max({p[0].x(), p[1].x(), p[2].x()}) + gutter;
    const double y_low = std::min({p[0].y(), p[1].y(), p[2].y()}) - gutter;
    const double y_high = std::max({p[0].y(), p[1].y(), p[2].y()}) + gutter;
    const int col_begin = std::max(0, static_cast<int>(std::floor(x_low - 0.5)));
    const int col_end = std::min(chart.width - 1, static_cast<int>(std::ceil(x_high - 0.5)));
    const int row_begin = std::max(0, static_cast<int>(std::floor(y_low - 0.5)));
    const int row_end = std::min(chart.height - 1, static_cast<int>(std::ceil(y_high - 0.5)));
    for (int row = row_begin; row <= row_end; ++row) {
      for (int col = col_begin; col <= col_end; ++col) {
        TexelOwner& owner = owners[static_cast<std::size_t>(row) * chart.width + col];
        if (owner.distance == 0.0f) continue;
        const Eigen::Vector2d q(col + 0.5, row + 0.5);
        if (std::abs(area2) > 1e-12) {
          const double b1 = ((q - p[0]).x() * (p[2] - p[0]).y() - (q - p[0]).y() * (p[2] - p[0]).x()) / area2;
          const double b2 = ((p[1] - p[0]).x() * (q - p[0]).y() - (p[1] - p[0]).y() * (q - p[0]).x()) / area2;
          if (b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0) {
            owner = {static_cast<int>(i), 0.0f, static_cast<float>(b1), static_cast<float>(b2)};
            continue;
          }
        }
        // Outside: the nearest point on the triangle's edges.
        double best = std::numeric_limits<double>::infinity();
        double b[3] = {1.0, 0.0, 0.0};
        for (int e = 0; e < 3; ++e) {
          const auto [distance_squared, t] = ClosestOnSegment(p[e], p[(e + 1) % 3], q);
          if (distance_squared < best) {
            best = distance_squared;
            b[0] = b[1] = b[2] = 0.0;
            b[e] = 1.0 - t;
            b[(e + 1) % 3] = t;
          }
        }
        const double distance = std::sqrt(best);
        if (distance <= gutter && distance < owner.distance) {
          owner = {static_cast<int>(i), static_cast<float>(distance), static_cast<float>(b[1]), static_cast<float>(b[2])};
        }
      }
    }
  }
  return owners;
}

std::vector<AtlasTexel> RasterizeChart(const TextureChart& chart, const AtlasPlacement& placement, double gutter) {
  const std::vector<TexelOwner> owners = FindTexelOwners(chart, gutter);
  // Face by face, row-major within a face: a counting sort by face index (the scan is row-major).
  std::vector<std::size_t> first_of_face(chart.faces.size() + 1, 0);
  for (const TexelOwner& owner : owners) {
    if (owner.face_index >= 0) ++first_of_face[static_cast<std::size_t>(owner.face_index) + 1];
  }
  for (std::size_t i = 0; i < chart.faces.size(); ++i) first_of_face[i + 1] += first_of_face[i];
  std::vector<AtlasTexel> texels(first_of_face.back());
  for (int row = 0; row < chart.height; ++row) {
    for (int col = 0; col < chart.width; ++col) {
      const TexelOwner& owner = owners[static_cast<std::size_t>(row) * chart.width + col];
      if (owner.face_index < 0) continue;
      AtlasTexel& texel = texels[first_of_face[static_cast<std::size_t>(owner.face_index)]++];
      texel.face = chart.faces[static_cast<std::size_t>(owner.face_index)];
      texel.page = static_cast<std::uint16_t>(placement.page);
      texel.x = static_cast<std::uint16_t>(placement.x + col);
      texel.y = static_cast<std::uint16_t>(placement.y + row);
      texel.b1 = owner.b1;
      texel.b2 = owner.b2;
    }
  }
  return texels;
}

}  // namespace

std::vector<std::size_t> CountChartTexels(const std::vector<TextureChart>& charts, double gutter, int num_threads) {
  std::vector<std::size_t> counts(charts.size());
  ParallelFor(charts.size(), num_threads, [&](std::size_t c) {
    const std::vector<TexelOwner> owners = FindTexelOwners(charts[c], gutter);
    counts[c] = static_cast<std::size_t>(
        std::count_if(owners.begin(), owners.end(), [](const TexelOwner& owner) { return owner.face_index >= 0; }));
  });
  return counts;
}

TexelLayout RasterizeTexels(const std::vector<TextureChart>& charts, const AtlasLayout& layout, std::size_t num_faces,
                            double gutter, int num_threads) {
  std::vector<std::size_t> all(charts.size());
  for (std::size_t c = 0; c < charts.size(); ++c) all[c] = c;
  return RasterizeTexels(charts, layout, all, num_faces, gutter, num_threads);
}

TexelLayout RasterizeTexels(const std::vector<TextureChart>& charts, const AtlasLayout& layout,
                            const std::vector<std::size_t>& chart_indices, std::size_t num_faces, double gutter,
                            int num_threads) {
  std::vector<std::vector<AtlasTexel>> per_chart(chart_indices.size());
  ParallelFor(chart_indices.size(), num_threads, [&](std::size_t i) {
    const std::size_t c = chart_indices.at(i);
    per_chart[i] = RasterizeChart(charts.at(c), layout.placements.at(c), gutter);
  });
  TexelLayout result;
  result.face_ranges.assign(num_faces, {0, 0});
  result.chart_offsets.push_back(0);
  std::size_t total = 0;
  for (const auto& texels : per_chart) total += texels.size();
  result.texels.reserve(total);
  for (auto& texels : per_chart) {
    for (std::size_t i = 0; i < texels.size();) {
      std::size_t j = i;
      while (j < texels.size() && texels[j].face == texels[i].face) ++j;
      result.face_ranges[texels[i].face] = {result.texels.size() + i, result.texels.size() + j};
      i = j;
    }
    result.texels.insert(result.texels.end(), texels.begin(), texels.end());
    result.chart_offsets.push_back(result.texels.size());
    std::vector<AtlasTexel>().swap(texels);
  }
  return result;
}

}  // namespace lutex
