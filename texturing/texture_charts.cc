#include "texturing/texture_charts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "texturing/view_selection.h"

namespace lutex {

namespace {

// Faces connected through shared edges with the same view, starting from `seed`.
std::vector<std::uint32_t> GrowComponent(std::uint32_t seed, const FaceAdjacency& adjacency,
                                         const std::vector<std::uint32_t>& view_of_face, std::vector<bool>& taken) {
  std::vector<std::uint32_t> faces{seed};
  taken[seed] = true;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (const std::uint32_t* n = adjacency.begin(faces[i]); n != adjacency.end(faces[i]); ++n) {
      if (!taken[*n] && view_of_face[*n] == view_of_face[seed]) {
        taken[*n] = true;
        faces.push_back(*n);
      }
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

// Projected corners of `faces` in `view`, scaled to texels (not yet shifted into a rectangle).
std::vector<Eigen::Vector2f> ProjectCorners(const Mesh& mesh, const TextureView& view,
                                            const std::vector<std::uint32_t>& faces, double texel_size) {
  double scale = 1.0;
  if (texel_size > 0.0) {
    // Scene units per pixel at a face = depth / focal length; its median over the chart sets the scale.
    std::vector<double> depths;
    depths.reserve(faces.size());
    for (std::uint32_t f : faces) {
      const Eigen::Vector3d centroid =
          (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]) / 3.0;
      depths.push_back((view.cam_from_world * centroid).z());
    }
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    const double focal = 0.5 * (view.camera.FocalLengthX() + view.camera.FocalLengthY());
    scale = depths[depths.size() / 2] / focal / texel_size;
  }
  std::vector<Eigen::Vector2f> corners;
  corners.reserve(3 * faces.size());
  for (std::uint32_t f : faces) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d pixel = view.camera.ImgFromCam(view.cam_from_world * mesh.vertices[mesh.faces[f][k]]);
      corners.push_back((pixel * scale).cast<float>());
    }
  }
  return corners;
}

// Shifts the corners so the chart's bounding box starts at (padding, padding); sets the size.
TextureChart MakeChart(std::uint32_t view, std::vector<std::uint32_t> faces, std::vector<Eigen::Vector2f> corners,
                       int padding) {
  Eigen::Vector2f low(std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity());
  Eigen::Vector2f high = -low;
  for (const Eigen::Vector2f& c : corners) {
    low = low.cwiseMin(c);
    high = high.cwiseMax(c);
  }
  const Eigen::Vector2f origin(std::floor(low.x()), std::floor(low.y()));
  TextureChart chart;
  chart.view = view;
  chart.faces = std::move(faces);
  chart.corner_texels = std::move(corners);
  for (Eigen::Vector2f& c : chart.corner_texels) c += Eigen::Vector2f::Constant(float(padding)) - origin;
  chart.width = static_cast<int>(std::ceil(high.x() - origin.x())) + 2 * padding;
  chart.height = static_cast<int>(std::ceil(high.y() - origin.y())) + 2 * padding;
  chart.width = std::max(chart.width, 2 * padding + 1);
  chart.height = std::max(chart.height, 2 * padding + 1);
  return chart;
}

}  // namespace

void TextureChartOptions::Check() const {
  if (!(texel_size >= 0.0) || !std::isfinite(texel_size)) throw std::invalid_argument("the texel size must be >= 0");
  if (padding < 0 || padding > 64) throw std::invalid_argument("the padding must be in [0, 64] texels");
  if (max_size < 64 + 4 * padding) {
    throw std::invalid_argument("the page size " + std::to_string(max_size) + " is too small for padding " +
                                std::to_string(padding));
  }
}

std::vector<TextureChart> BuildTextureCharts(const Mesh& mesh, const FaceAdjacency& adjacency,
                                             const std::vector<TextureView>& views,
                                             const std::vector<std::uint32_t>& view_of_face,
                                             const TextureChartOptions& options) {
  options.Check();
  std::vector<TextureChart> charts;
  std::vector<bool> taken(mesh.faces.size(), false);
  // Charts bigger than a page are tiled; a tile leaves half a page of room for faces crossing its border.
  const float tile = 0.5f * static_cast<float>(options.max_size - 2 * options.padding);
  for (std::uint32_t seed = 0; seed < mesh.faces.size(); ++seed) {
    if (taken[seed] || view_of_face[seed] == kNoView) continue;
    const std::uint32_t view = view_of_face[seed];
    std::vector<std::uint32_t> faces = GrowComponent(seed, adjacency, view_of_face, taken);
    std::vector<Eigen::Vector2f> corners = ProjectCorners(mesh, views[view], faces, options.texel_size);
    TextureChart chart = MakeChart(view, faces, corners, options.padding);
    if (chart.width <= options.max_size && chart.height <= options.max_size) {
      charts.push_back(std::move(chart));
      continue;
    }
    std::map<std::pair<int, int>, std::pair<std::vector<std::uint32_t>, std::vector<Eigen::Vector2f>>> tiles;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const Eigen::Vector2f centroid = (corners[3 * i] + corners[3 * i + 1] + corners[3 * i + 2]) / 3.0f;
      auto& [tile_faces, tile_corners] = tiles[{static_cast<int>(std::floor(centroid.y() / tile)),
                                                static_cast<int>(std::floor(centroid.x() / tile))}];
      tile_faces.push_back(faces[i]);
      tile_corners.insert(tile_corners.end(), corners.begin() + 3 * i, corners.begin() + 3 * i + 3);
    }
    for (auto& [key, tile_data] : tiles) {
      charts.push_back(MakeChart(view, std::move(tile_data.first), std::move(tile_data.second), options.padding));
    }
  }
  return charts;
}

}  // namespace lutex
