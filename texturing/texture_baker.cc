#include "texturing/texture_baker.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <limits>
#include <stdexcept>

#include "lib/geometry/spatial_batches.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"
#include "lib/util/parallel_for.h"
#include "texturing/atlas_packing.h"
#include "texturing/face_adjacency.h"
#include "texturing/texel_layout.h"
#include "texturing/texture_fill.h"
#include "texturing/tile_mesh.h"

namespace lutex {

namespace {

constexpr const char* kFitTheAtlas = "; write a format without that limit, or raise {max_size} or {texel_size}";

std::string PagesHeld(const TextureBakingOptions& options) {
  return options.max_pages_reason.empty() ? "the output holds " + std::to_string(options.max_pages)
                                          : options.max_pages_reason;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void CheckAtlasFits(const Mesh& mesh, const TextureBakingOptions& options) {
  if (options.max_pages == 0 || options.charts.texel_size <= 0.0) return;
  double area = 0.0;
  for (const auto& face : mesh.faces) {
    area += 0.5 * (mesh.vertices[face[1]] - mesh.vertices[face[0]]).cross(mesh.vertices[face[2]] - mesh.vertices[face[0]]).norm();
  }
  const double texels = area / (options.charts.texel_size * options.charts.texel_size);
  const double page_texels = double(options.charts.max_size) * double(options.charts.max_size);
  if (texels > page_texels * double(options.max_pages)) {
    const double pages = std::ceil(texels / page_texels);
    std::ostringstream texel_size;
    texel_size << options.charts.texel_size;
    throw OptionError("the mesh's " + std::to_string(std::lround(area)) + " square units at {texel_size} " +
                      texel_size.str() + " need at least " + std::to_string(std::int64_t(pages)) + " pages of " +
                      std::to_string(options.charts.max_size) + " texels, but " + PagesHeld(options) + kFitTheAtlas);
  }
}

void TextureBakingOptions::Check() const {
  visibility.Check();
  selection.Check();
  levelling.Check();
  charts.Check();
  if (!(gutter >= 0.0 && gutter <= charts.padding + 0.5)) {
    throw std::invalid_argument("the gutter must be in [0, padding + 0.5] texels");
  }
  if (fusion.memory_limit_bytes == 0) throw std::invalid_argument("the memory limit must be positive");
}

TextureBakingResult BakeTexture(const Mesh& mesh, const std::vector<TextureView>& views, const ViewImageSource& source,
                                const TextureBakingOptions& options) {
  options.Check();
  mesh.Check("texture: mesh");
  return BakeTexture(mesh, RaycastScene(mesh), views, source, options);
}

ChosenViews ChooseViews(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                        const ViewRaycaster& raycaster, const ViewImageSource& source,
                        const TextureBakingOptions& options, const ViewChoicePart* part) {
  auto start = std::chrono::steady_clock::now();
  FaceViewCandidatesOptions visibility = options.visibility;
  visibility.num_threads = options.num_threads;
  visibility.show_progress = visibility.show_progress && !part;
  ChosenViews chosen{part ? FindFaceViewCandidates(mesh, adjacency, views, raycaster, source, visibility, part->casts)
                          : FindFaceViewCandidates(mesh, adjacency, views, raycaster, source, visibility),
                     {}, {}, {}, 0.0, 0.0};
  chosen.seconds_visibility = SecondsSince(start);
  start = std::chrono::steady_clock::now();
  chosen.selection = SelectViews(chosen.candidates, adjacency, options.selection,
                                 part ? part->given : std::vector<std::uint32_t>());
  chosen.seconds_selection = SecondsSince(start);
  chosen.candidates.DropQualities();
  TexelFusionOptions fusion = options.fusion;
  fusion.num_threads = options.num_threads;
  fusion.show_progress = fusion.show_progress && !part;
  SeamLevellingPart levelling_part;
  if (part) {
    levelling_part.levelled_here.resize(mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) levelling_part.levelled_here[f] = part->given[f] == kChooseView;
    levelling_part.shown = part->shown;
    levelling_part.settled = part->settled;
  }
  chosen.corrections = LevelSeams(mesh, adjacency, views, raycaster, source, chosen.candidates,
                                  chosen.selection.view_of_face, fusion, options.levelling, &chosen.levelling,
                                  part ? &levelling_part : nullptr);
  return chosen;
}

namespace {

// The batches of charts that BakeLabelledFaces lays out and fuses together, each of at most
// `texels_per_batch` texels (a larger chart alone): all charts at once when their rectangles fit, else
// batches of neighbours along the surface (spatial_batches.h) by each chart's exact texel count and its
// centroid with faces weighed by their area in texels, where its texels are.
std::vector<std::vector<std::size_t>> PlanChartBatches(const Mesh& mesh, const std::vector<TextureChart>& charts,
                                                       double gutter, std::size_t texels_per_batch, int num_threads) {
  std::size_t rectangle_texels = 0;  // bounds the charts' texels from above
  for (const TextureChart& chart : charts) {
    rectangle_texels += static_cast<std::size_t>(chart.width) * static_cast<std::size_t>(chart.height);
  }
  if (rectangle_texels <= texels_per_batch) {
    std::vector<std::size_t> all(charts.size());
    for (std::size_t c = 0; c < charts.size(); ++c) all[c] = c;
    return charts.empty() ? std::vector<std::vector<std::size_t>>() : std::vector<std::vector<std::size_t>>{all};
  }
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& vertex : mesh.vertices) bounds.extend(vertex);
  std::vector<Eigen::Vector3d> centroids(charts.size(), Eigen::Vector3d::Zero());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    double total = 0.0;
    for (std::size_t i = 0; i < charts[c].faces.size(); ++i) {
      const Eigen::Vector2f* corner = &charts[c].corner_texels[3 * i];
      const Eigen::Vector2f a = corner[1] - corner[0], b = corner[2] - corner[0];
      const double texels = 0.5 * std::abs(double(a.x()) * b.y() - double(a.y()) * b.x()) + 1e-6;
      const Mesh::Face& face = mesh.faces[charts[c].faces[i]];
      centroids[c] += texels / 3.0 * (mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]);
      total += texels;
    }
    if (total > 0.0) centroids[c] /= total;
  }
  return BatchAlongMortonCurve(centroids, CountChartTexels(charts, gutter, num_threads), bounds, texels_per_batch);
}

}  // namespace

void BakeLabelledFaces(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                       const std::vector<std::uint32_t>& view_of_face, const TextureBakingOptions& options,
                       bool show_progress, const TexelColouring& colour, TexturedMesh& textured,
                       TextureBakingSummary& summary) {
  auto start = std::chrono::steady_clock::now();
  const std::vector<TextureChart> charts = BuildTextureCharts(mesh, adjacency, views, view_of_face, options.charts);
  std::vector<cv::Size> rectangles;
  rectangles.reserve(charts.size());
  for (const TextureChart& chart : charts) rectangles.emplace_back(chart.width, chart.height);
  const AtlasLayout atlas = PackAtlas(rectangles, options.charts.max_size);
  if (options.max_pages > 0 && atlas.page_sizes.size() > options.max_pages) {
    throw OptionError("the atlas needs " + std::to_string(atlas.page_sizes.size()) + " pages of up to " +
                      std::to_string(options.charts.max_size) + " texels, but " + PagesHeld(options) + kFitTheAtlas);
  }
  summary.seconds_layout += SecondsSince(start);

  // The texels are laid out and coloured a batch of neighbouring charts at a time, so that the texel
  // table and the colouring's samples are held for one batch only (bounded by the fusion's memory limit).
  start = std::chrono::steady_clock::now();
  textured.pages.clear();
  for (const cv::Size& size : atlas.page_sizes) {
    textured.pages.emplace_back(size, CV_32FC3, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
    summary.page_texels += static_cast<std::size_t>(size.area());
  }
  const std::size_t texels_per_batch =
      std::max<std::size_t>(1, options.fusion.memory_limit_bytes / (sizeof(AtlasTexel) + FusionBytesPerTexel()));
  const auto counting_start = std::chrono::steady_clock::now();
  const std::vector<std::vector<std::size_t>> batches =
      PlanChartBatches(mesh, charts, options.gutter, texels_per_batch, options.num_threads);
  double seconds_rasterising = SecondsSince(counting_start);
  if (show_progress) {
    LogInfo() << "texture: " << charts.size() << " charts on " << atlas.page_sizes.size() << " pages"
              << (batches.size() > 1 ? ", coloured in " + std::to_string(batches.size()) + " parts" : "");
  }
  for (std::size_t b = 0; b < batches.size(); ++b) {
    const auto layout_start = std::chrono::steady_clock::now();
    const TexelLayout layout =
        RasterizeTexels(charts, atlas, batches[b], mesh.faces.size(), options.gutter, options.num_threads);
    seconds_rasterising += SecondsSince(layout_start);
    colour(layout, b, batches.size(), textured.pages);
    summary.num_texels += layout.texels.size();
  }
  for (cv::Mat& page : textured.pages) FillUnknownTexels(page, options.num_threads);
  summary.seconds_layout += seconds_rasterising;
  summary.seconds_fusion += SecondsSince(start) - seconds_rasterising;

  textured.face_page.assign(mesh.faces.size(), -1);
  textured.face_corner_texels.assign(mesh.faces.size(), {});
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const Eigen::Vector2f offset(static_cast<float>(atlas.placements[c].x), static_cast<float>(atlas.placements[c].y));
    for (std::size_t i = 0; i < charts[c].faces.size(); ++i) {
      const std::uint32_t face = charts[c].faces[i];
      textured.face_page[face] = atlas.placements[c].page;
      for (int k = 0; k < 3; ++k) textured.face_corner_texels[face][k] = charts[c].corner_texels[3 * i + k] + offset;
    }
  }
  summary.num_charts += charts.size();
  summary.num_pages += atlas.page_sizes.size();
}

namespace {

// Colours the faces with the texel fusion from the views and the seam levelling's corrections.
// `source_vertex` as for ApplySeamCorrections (seam_levelling.h).
void BakeFusedFaces(const Mesh& mesh, const FaceAdjacency& adjacency, const std::vector<TextureView>& views,
                    const ViewRaycaster& raycaster, const ViewImageSource& source,
                    const FaceViewCandidates& candidates, const std::vector<std::uint32_t>& view_of_face,
                    const SeamCorrections& corrections, const std::vector<std::uint32_t>& source_vertex,
                    const TextureBakingOptions& options, bool show_progress, TexturedMesh& textured,
                    TextureBakingSummary& summary) {
  TexelFusionOptions fusion = options.fusion;
  fusion.num_threads = options.num_threads;
  fusion.show_progress = fusion.show_progress && show_progress;
  const std::string progress_label = fusion.progress_label;
  const TexelColouring fuse = [&](const TexelLayout& layout, std::size_t batch, std::size_t num_batches,
                                  std::vector<cv::Mat>& pages) {
    if (num_batches > 1) {
      fusion.progress_label =
          progress_label + ", part " + std::to_string(batch + 1) + "/" + std::to_string(num_batches);
    }
    summary.fusion.Add(FuseTexels(mesh, views, raycaster, source, candidates, view_of_face, layout, fusion, pages));
    ApplySeamCorrections(mesh, view_of_face, corrections, source_vertex, layout, options.num_threads, pages);
  };
  BakeLabelledFaces(mesh, adjacency, views, view_of_face, options, show_progress, fuse, textured, summary);
}

}  // namespace

TextureBakingResult BakeTexture(const Mesh& mesh, const RaycastScene& scene, const std::vector<TextureView>& views,
                                const ViewImageSource& source, const TextureBakingOptions& options) {
  options.Check();
  CheckAtlasFits(mesh, options);
  if (views.empty()) throw std::invalid_argument("texture: no views to texture from");
  if (!source.linear_rgb) throw std::invalid_argument("texture: no image source");
  if (views.size() >= kNoView) throw std::invalid_argument("texture: too many views");
  mesh.Check("texture: mesh");
  TextureBakingResult result;
  TextureBakingSummary& summary = result.summary;
  summary.num_views = views.size();
  summary.num_faces = mesh.faces.size();

  const ViewRaycaster raycaster(scene);
  const FaceAdjacency adjacency(mesh);
  ChosenViews chosen = ChooseViews(mesh, adjacency, views, raycaster, source, options);
  summary.seconds_visibility = chosen.seconds_visibility;
  summary.seconds_selection = chosen.seconds_selection;
  summary.levelling = chosen.levelling;
  TexturedMesh& textured = result.textured;
  textured.mesh = mesh;
  BakeFusedFaces(mesh, adjacency, views, raycaster, source, chosen.candidates, chosen.selection.view_of_face,
                 chosen.corrections, /*source_vertex=*/{}, options, /*show_progress=*/true, textured, summary);
  summary.num_textured_faces = textured.NumTexturedFaces();
  summary.seams = MeasureSeamVisibility(textured, adjacency);
  result.view_of_face = std::move(chosen.selection.view_of_face);
  chosen.selection.view_of_face.clear();
  summary.selection = chosen.selection;
  return result;
}

TexturedMesh BakeFaces(const Mesh& mesh, const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                       const ViewImageSource& source, const ChosenViews& chosen, const std::vector<std::uint32_t>& faces,
                       const TextureBakingOptions& options, std::vector<std::uint32_t>& source_vertex,
                       TextureBakingSummary& summary) {
  options.Check();
  const std::vector<std::uint32_t>& labels = chosen.selection.view_of_face;
  if (labels.size() != mesh.faces.size()) throw std::invalid_argument("texture: the views were chosen for another mesh");
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] >= mesh.faces.size() || (i > 0 && faces[i] <= faces[i - 1])) {
      throw std::invalid_argument("texture: the faces to bake must be ascending faces of the mesh");
    }
  }
  // The faces' own mesh and tables, so that the work and memory are those of the faces, not of the mesh.
  // Depth tests against the whole mesh's ray casts keep occlusion by the rest of the surface.
  TileMesh part = ExtractTileMesh(mesh, faces);
  source_vertex = std::move(part.source_vertex);
  TexturedMesh textured;
  textured.mesh = std::move(part.mesh);
  const FaceAdjacency adjacency(textured.mesh);
  const FaceViewCandidates candidates = chosen.candidates.Subset(faces);
  std::vector<std::uint32_t> view_of_face(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) view_of_face[i] = labels[faces[i]];
  BakeFusedFaces(textured.mesh, adjacency, views, raycaster, source, candidates, view_of_face, chosen.corrections,
                 source_vertex, options, /*show_progress=*/false, textured, summary);
  summary.num_views = views.size();
  summary.num_faces += faces.size();
  summary.num_textured_faces += textured.NumTexturedFaces();
  return textured;
}

}  // namespace lutex
