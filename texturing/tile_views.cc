#include "texturing/tile_views.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "texturing/face_adjacency.h"
#include "texturing/view_selection.h"

namespace lutex {

namespace {

// Points sampled along each side of an image for its extent (a distortion bends the sides between them).
constexpr int kBorderSamples = 16;
// The extent grows by this fraction of its width on each side: a margin for the bending between samples.
constexpr double kExtentMargin = 0.05;

std::uint64_t SettledKey(std::uint32_t vertex, std::uint32_t view) { return std::uint64_t(vertex) << 32 | view; }

}  // namespace

TiledViewChoice::TiledViewChoice(const Mesh& mesh, const std::vector<TextureView>& views,
                                 const std::vector<const std::vector<std::uint32_t>*>& tiles,
                                 const TextureBakingOptions& options, const std::filesystem::path& scratch,
                                 const std::vector<Eigen::AlignedBox3d>& spans)
    : views_(views), options_(options), strides_(CastEveryView(mesh, views, options.visibility.rays_per_face)),
      mesh_file_(mesh, tiles, scratch, kChooseView) {
  options_.Check();
  if (!spans.empty() && spans.size() != tiles.size()) throw std::invalid_argument("tiled views: one span per tile");
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    Eigen::AlignedBox3d box = mesh_file_.box(t);
    if (!spans.empty()) box.extend(spans[t]);
    tile_boxes_.push_back(box);
  }
  for (const Mesh::Face& face : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      longest_edge_ = std::max(longest_edge_, (mesh.vertices[face[k]] - mesh.vertices[face[(k + 1) % 3]]).norm());
    }
  }
  for (const TextureView& view : views) {
    const double width = double(view.camera.width), height = double(view.camera.height);
    Eigen::Vector4d extent(INFINITY, -INFINITY, INFINITY, -INFINITY);
    for (int i = 0; i <= kBorderSamples; ++i) {
      const double s = double(i) / kBorderSamples;
      for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(s * width, 0.0), Eigen::Vector2d(s * width, height),
                                           Eigen::Vector2d(0.0, s * height), Eigen::Vector2d(width, s * height)}) {
        const Eigen::Vector3d ray = view.camera.CamFromImg(pixel);
        extent = Eigen::Vector4d(std::min(extent[0], ray.x()), std::max(extent[1], ray.x()),
                                 std::min(extent[2], ray.y()), std::max(extent[3], ray.y()));
      }
    }
    const double grow_x = kExtentMargin * (extent[1] - extent[0]), grow_y = kExtentMargin * (extent[3] - extent[2]);
    view_extent_.emplace_back(extent[0] - grow_x, extent[1] + grow_x, extent[2] - grow_y, extent[3] + grow_y);
  }
}

bool TiledViewChoice::MaySee(std::size_t view, const Eigen::AlignedBox3d& box) const {
  const Eigen::Vector4d& extent = view_extent_[view];
  // Each side of the frustum as a half-space through the camera's centre, n . point_in_cam <= 0 inside.
  const std::array<Eigen::Vector3d, 5> outward = {
      Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d(1.0, 0.0, -extent[1]), Eigen::Vector3d(-1.0, 0.0, extent[0]),
      Eigen::Vector3d(0.0, 1.0, -extent[3]), Eigen::Vector3d(0.0, -1.0, extent[2])};
  std::array<Eigen::Vector3d, 8> corners_in_cam;
  for (int c = 0; c < 8; ++c) {
    corners_in_cam[c] = views_[view].cam_from_world * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
  }
  for (const Eigen::Vector3d& n : outward) {
    bool all_outside = true;
    for (const Eigen::Vector3d& corner : corners_in_cam) all_outside = all_outside && n.dot(corner) > 0.0;
    if (all_outside) return false;
  }
  return true;
}

TilePiece TiledViewChoice::Choose(std::size_t tile, const ViewImageSource& source, const TileUse* use) {
  const auto start = std::chrono::steady_clock::now();
  if (tile >= tile_boxes_.size()) throw std::out_of_range("tiled views: no such tile");
  Eigen::AlignedBox3d grown = tile_boxes_[tile];
  grown.min().array() -= longest_edge_;
  grown.max().array() += longest_edge_;

  // The views that may see the tile or the faces next to it, and the box their rays to it stay in.
  ViewChoicePart part;
  part.casts.stride_of_view = strides_.stride_of_view;
  part.casts.faces_within = grown;
  Eigen::AlignedBox3d reach = grown;
  for (std::size_t v = 0; v < views_.size(); ++v) {
    if (!MaySee(v, grown)) continue;
    part.casts.views.push_back(static_cast<std::uint32_t>(v));
    reach.extend(views_[v].cam_from_world.TargetOriginInSource());
  }
  std::vector<std::size_t> near;
  for (std::size_t t = 0; t < tile_boxes_.size(); ++t) {
    if (tile_boxes_[t].intersects(reach)) near.push_back(t);
  }
  TiledMeshFile::Piece read = mesh_file_.Read(near, [&](std::size_t t, const Eigen::AlignedBox3d& face_box) {
    return t == tile || face_box.intersects(reach);
  });
  const std::vector<std::uint32_t>& piece_faces = read.mesh_face;
  if (piece_faces.empty()) {  // nothing within reach: no scene
    return TilePiece{{}, {}, nullptr, nullptr, ChosenViews{FaceViewCandidates(0, 1), {}, {}, {}, 0.0, 0.0}};
  }

  TileMesh& piece = read.tile_mesh;
  std::vector<bool> shown(piece_faces.size(), false);
  if (use) {
    for (std::uint32_t i : use->shown(piece)) shown.at(i) = true;
  }
  // Chosen here: the tile's faces and the shown ones that no tile chose before.
  std::vector<std::uint32_t> tile_faces;
  part.given.resize(piece_faces.size());
  std::vector<bool> here(piece_faces.size(), false);
  for (std::size_t i = 0; i < piece_faces.size(); ++i) {
    const bool chosen_before = read.label[i] != kChooseView;
    here[i] = !chosen_before && (shown[i] || read.tile[i] == tile);
    if (here[i]) tile_faces.push_back(static_cast<std::uint32_t>(i));
    part.given[i] = here[i] ? kChooseView : chosen_before ? read.label[i] : kNoView;
    shown[i] = shown[i] && !here[i];
  }
  if (use) part.shown = std::move(shown);
  const std::vector<std::uint32_t>& source_vertex = piece.source_vertex;
  part.settled = [&](std::uint32_t vertex, std::uint32_t view) {
    const auto found = settled_.find(SettledKey(source_vertex[vertex], view));
    return found == settled_.end() ? Eigen::Vector3f::Zero().eval() : found->second;
  };
  auto scene = std::make_unique<RaycastScene>(piece.mesh);
  auto raycaster = std::make_unique<ViewRaycaster>(*scene, rays_);
  ChosenViews chosen = ChooseViews(piece.mesh, FaceAdjacency(piece.mesh), views_, *raycaster, source, options_, &part);

  // What the tiles after this one need: its labels, and its corrections where its faces meet others and
  // at every corner of the faces a later tile may show.
  {
    std::vector<std::uint32_t> faces, tiles, labels;
    for (std::uint32_t i : tile_faces) {
      faces.push_back(piece_faces[i]);
      tiles.push_back(read.tile[i]);
      labels.push_back(chosen.selection.view_of_face[i]);
    }
    mesh_file_.SetLabels(faces, tiles, labels);
  }
  std::vector<std::uint8_t> used_by(piece.mesh.vertices.size(), 0);  // 1: a face here, 2: another, 3: both
  for (std::size_t i = 0; i < piece_faces.size(); ++i) {
    for (std::uint32_t v : piece.mesh.faces[i]) used_by[v] = static_cast<std::uint8_t>(used_by[v] | (here[i] ? 1 : 2));
  }
  if (use && use->shown_later) {
    for (std::uint32_t i : tile_faces) {
      if (!use->shown_later(i)) continue;
      for (std::uint32_t v : piece.mesh.faces[i]) used_by[v] = 3;
    }
  }
  std::vector<std::pair<std::uint32_t, Eigen::Vector3f>> at_vertex;
  for (std::uint32_t v = 0; v < used_by.size(); ++v) {
    if (used_by[v] != 3) continue;
    at_vertex.clear();
    chosen.corrections.AppendAt(v, &at_vertex);
    for (const auto& [view, correction] : at_vertex) settled_[SettledKey(source_vertex[v], view)] = correction;
  }

  const SeamLevellingSummary& levelled = chosen.levelling;
  const double points = double(levelling_.num_seam_points), more = double(levelled.num_seam_points);
  if (points + more > 0.0) {
    levelling_.step_before = (levelling_.step_before * points + levelled.step_before * more) / (points + more);
    levelling_.step_after = (levelling_.step_after * points + levelled.step_after * more) / (points + more);
  }
  levelling_.enabled = levelled.enabled;
  levelling_.num_seam_points += levelled.num_seam_points;
  levelling_.num_unknowns += levelled.num_unknowns;
  levelling_.iterations = std::max(levelling_.iterations, levelled.iterations);
  levelling_.seconds += levelled.seconds;
  max_piece_faces_ = std::max(max_piece_faces_, piece_faces.size());
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return TilePiece{std::move(piece), std::move(tile_faces), std::move(scene), std::move(raycaster), std::move(chosen)};
}

}  // namespace lutex
