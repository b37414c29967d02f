#include "texturing/face_view_candidates.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <string>
#include <cmath>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "lib/util/logging.h"
#include "lib/util/parallel_for.h"
#include "lib/util/progress.h"

namespace lutex {

namespace {

// Pixel statistics of one view, per face, reset after each view (only touched entries).
struct FaceHits {
  std::vector<std::uint32_t> hits;
  std::vector<float> confidence_sum;
  std::vector<std::uint32_t> touched;

  void Resize(std::size_t num_faces) {
    if (hits.size() == num_faces) return;
    hits.assign(num_faces, 0);
    confidence_sum.assign(num_faces, 0.0f);
  }
  void Clear() {
    for (std::uint32_t face : touched) {
      hits[face] = 0;
      confidence_sum[face] = 0.0f;
    }
    touched.clear();
  }
};

// How many rays of a cast at every `stride`-th pixel (through the pixel centres (stride c + stride / 2 +
// 0.5, stride r + stride / 2 + 0.5), the grid continued beyond the image) fall inside the projected
// triangle `pixels`: what a face would be hit by if nothing hid it and the image had no edge. A face that
// the image's edge cuts is thus as partly seen as a face that something hides.
int RaysInside(const std::array<Eigen::Vector2d, 3>& pixels, int stride) {
  const auto table_index = [stride](double pixel) { return (pixel - 0.5 - stride / 2) / stride; };
  const double x_min = std::min({pixels[0].x(), pixels[1].x(), pixels[2].x()});
  const double x_max = std::max({pixels[0].x(), pixels[1].x(), pixels[2].x()});
  const double y_min = std::min({pixels[0].y(), pixels[1].y(), pixels[2].y()});
  const double y_max = std::max({pixels[0].y(), pixels[1].y(), pixels[2].y()});
  const int col_first = static_cast<int>(std::ceil(table_index(x_min)));
  const int col_last = static_cast<int>(std::floor(table_index(x_max)));
  const int row_first = static_cast<int>(std::ceil(table_index(y_min)));
  const int row_last = static_cast<int>(std::floor(table_index(y_max)));
  // Signed edge functions, all of one sign inside (either orientation).
  const auto edge = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double x, double y) {
    return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
  };
  int inside = 0;
  for (int row = row_first; row <= row_last; ++row) {
    const double y = stride * row + stride / 2 + 0.5;
    for (int col = col_first; col <= col_last; ++col) {
      const double x = stride * col + stride / 2 + 0.5;
      const double e0 = edge(pixels[0], pixels[1], x, y), e1 = edge(pixels[1], pixels[2], x, y),
                   e2 = edge(pixels[2], pixels[0], x, y);
      inside += (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
    }
  }
  return inside;
}

// Rays of the strided table around `box`'s projection into `view` (VisibilityCasts::faces_within): its
// edges sampled (a distortion bends them), grown by kWindowMargin rays and clipped to the table. The whole
// table when part of the box is behind the camera; an empty rectangle when the box is off the image.
constexpr int kWindowMargin = 3;
cv::Rect CastWindow(const TextureView& view, const Eigen::AlignedBox3d& box, int stride, bool* whole) {
  constexpr int kEdgeSamples = 8;
  *whole = false;
  double x_min = INFINITY, x_max = -INFINITY, y_min = INFINITY, y_max = -INFINITY;
  for (int a = 0; a < 8; ++a) {
    for (int axis = 0; axis < 3; ++axis) {
      if (a & (1 << axis)) continue;  // each edge once: from a corner along an axis it is low on
      const Eigen::Vector3d from = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(a));
      const Eigen::Vector3d to = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(a | (1 << axis)));
      for (int i = 0; i <= kEdgeSamples; ++i) {
        const Eigen::Vector3d point_in_cam = view.cam_from_world * (from + (to - from) * (double(i) / kEdgeSamples));
        if (!(point_in_cam.z() > 0.0)) {
          *whole = true;
          return cv::Rect();
        }
        const Eigen::Vector2d pixel = view.camera.ImgFromCam(point_in_cam);
        x_min = std::min(x_min, pixel.x());
        x_max = std::max(x_max, pixel.x());
        y_min = std::min(y_min, pixel.y());
        y_max = std::max(y_max, pixel.y());
      }
    }
  }
  if (!(std::isfinite(x_min) && std::isfinite(x_max) && std::isfinite(y_min) && std::isfinite(y_max))) {
    *whole = true;
    return cv::Rect();
  }
  const int cols = (static_cast<int>(view.camera.width) + stride - 1) / stride;
  const int rows = (static_cast<int>(view.camera.height) + stride - 1) / stride;
  const double first_col = std::max(0.0, std::floor(x_min / stride) - kWindowMargin);
  const double first_row = std::max(0.0, std::floor(y_min / stride) - kWindowMargin);
  const double end_col = std::min(double(cols), std::ceil(x_max / stride) + kWindowMargin + 1);
  const double end_row = std::min(double(rows), std::ceil(y_max / stride) + kWindowMargin + 1);
  if (!(end_col > first_col && end_row > first_row)) return cv::Rect();
  return cv::Rect(static_cast<int>(first_col), static_cast<int>(first_row), static_cast<int>(end_col - first_col),
                  static_cast<int>(end_row - first_row));
}

bool Better(const FaceViewCandidate& a, const FaceViewCandidate& b) {
  return a.quality > b.quality || (a.quality == b.quality && a.view < b.view);
}

}  // namespace

void FaceViewCandidatesOptions::Check() const {
  if (max_views_per_face < 1 || max_views_per_face > 255) {
    throw std::invalid_argument("max views per face must be in [1, 255], got " + std::to_string(max_views_per_face));
  }
  if (!(min_cos_angle >= 0.0 && min_cos_angle < 1.0)) {
    throw std::invalid_argument("the minimum cosine of the viewing angle must be in [0, 1)");
  }
  if (rays_per_face < 0) throw std::invalid_argument("rays per face must be 0 or more, got " + std::to_string(rays_per_face));
}

int VisibilityStride(const Mesh& mesh, const TextureView& view, int rays_per_face) {
  constexpr std::size_t kSampleFaces = 4000;
  if (rays_per_face == 0) return 1;
  const std::size_t step = std::max<std::size_t>(1, mesh.faces.size() / kSampleFaces);
  std::vector<double> areas;
  for (std::size_t face = 0; face < mesh.faces.size(); face += step) {
    std::array<Eigen::Vector2d, 3> pixels;
    bool in_front = true;
    for (int k = 0; k < 3 && in_front; ++k) {
      const Eigen::Vector3d point_in_cam = view.cam_from_world * mesh.vertices[mesh.faces[face][k]];
      in_front = point_in_cam.z() > 0.0;
      if (in_front) pixels[k] = view.camera.ImgFromCam(point_in_cam);
    }
    if (!in_front) continue;
    const Eigen::Vector2d centroid = (pixels[0] + pixels[1] + pixels[2]) / 3.0;
    if (!(centroid.x() >= 0.0 && centroid.y() >= 0.0 && centroid.x() < double(view.camera.width) &&
          centroid.y() < double(view.camera.height))) {
      continue;
    }
    const Eigen::Vector2d u = pixels[1] - pixels[0], v = pixels[2] - pixels[0];
    const double area = 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
    if (std::isfinite(area)) areas.push_back(area);
  }
  if (areas.empty()) return 1;
  std::nth_element(areas.begin(), areas.begin() + static_cast<std::ptrdiff_t>(areas.size() / 2), areas.end());
  const double median_area = areas[areas.size() / 2];
  const int stride = static_cast<int>(std::floor(std::sqrt(median_area / double(rays_per_face))));
  return std::clamp(stride, 1, kMaxVisibilityStride);
}

FaceViewCandidates::FaceViewCandidates(std::size_t num_faces, int max_views_per_face)
    : stride_(static_cast<std::size_t>(max_views_per_face)),
      views_(num_faces * stride_),
      qualities_(num_faces * stride_),
      counts_(num_faces, 0) {}

void FaceViewCandidates::RequireQualities() const {
  if (qualities_.empty() && !views_.empty()) throw std::logic_error("face view candidates: the qualities were dropped");
}

float FaceViewCandidates::Quality(std::uint32_t face, std::size_t i) const {
  RequireQualities();
  return qualities_[face * stride_ + i];
}

FaceViewCandidates FaceViewCandidates::Subset(const std::vector<std::uint32_t>& faces) const {
  FaceViewCandidates subset(faces.size(), static_cast<int>(stride_));
  if (qualities_.empty()) subset.DropQualities();
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::size_t from = faces[i] * stride_, count = counts_.at(faces[i]);
    std::copy_n(views_.begin() + from, count, subset.views_.begin() + i * stride_);
    if (!qualities_.empty()) std::copy_n(qualities_.begin() + from, count, subset.qualities_.begin() + i * stride_);
    subset.counts_[i] = static_cast<std::uint8_t>(count);
  }
  return subset;
}

void FaceViewCandidates::DropQualities() {
  qualities_.clear();
  qualities_.shrink_to_fit();
}

void FaceViewCandidates::Offer(std::uint32_t face, const FaceViewCandidate& candidate) {
  RequireQualities();
  std::uint32_t* views = views_.data() + face * stride_;
  float* qualities = qualities_.data() + face * stride_;
  const auto at = [&](std::size_t i) { return FaceViewCandidate{views[i], qualities[i]}; };
  std::size_t count = counts_[face];
  if (count == stride_ && !Better(candidate, at(count - 1))) return;
  if (count < stride_) ++count;
  std::size_t i = count - 1;
  while (i > 0 && Better(candidate, at(i - 1))) {
    views[i] = views[i - 1];
    qualities[i] = qualities[i - 1];
    --i;
  }
  views[i] = candidate.view;
  qualities[i] = candidate.quality;
  counts_[face] = static_cast<std::uint8_t>(count);
}

VisibilityCasts CastEveryView(const Mesh& mesh, const std::vector<TextureView>& views, int rays_per_face) {
  VisibilityCasts casts;
  for (std::size_t v = 0; v < views.size(); ++v) {
    casts.views.push_back(static_cast<std::uint32_t>(v));
    casts.stride_of_view.push_back(VisibilityStride(mesh, views[v], rays_per_face));
  }
  return casts;
}

FaceViewCandidates FindFaceViewCandidates(const Mesh& mesh, const FaceAdjacency& adjacency,
                                          const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                                          const ViewImageSource& source, const FaceViewCandidatesOptions& options) {
  options.Check();
  return FindFaceViewCandidates(mesh, adjacency, views, raycaster, source, options,
                                CastEveryView(mesh, views, options.rays_per_face));
}

FaceViewCandidates FindFaceViewCandidates(const Mesh& mesh, const FaceAdjacency& adjacency,
                                          const std::vector<TextureView>& views, const ViewRaycaster& raycaster,
                                          const ViewImageSource& source, const FaceViewCandidatesOptions& options,
                                          const VisibilityCasts& casts) {
  options.Check();
  if (casts.stride_of_view.size() != views.size()) throw std::invalid_argument("visibility: one stride per view needed");
  const std::size_t num_faces = mesh.faces.size();
  FaceViewCandidates candidates(num_faces, options.max_views_per_face);
  constexpr std::size_t kNumLocks = 1024;
  std::vector<std::mutex> locks(kNumLocks);
  std::optional<ProgressReporter> progress;
  if (options.show_progress) progress.emplace("texture: visibility", casts.views.size(), "views");
  std::array<std::atomic<int>, kMaxVisibilityStride + 1> views_by_stride{};
  constexpr std::array<const char*, kMaxVisibilityStride + 1> kOrdinals = {"", "", "2nd", "3rd", "4th"};
  // The maps of the view each worker is on, reused from view to view.
  std::vector<GeometryMaps> worker_maps(static_cast<std::size_t>(ResolveNumThreads(options.num_threads)));
  ParallelForOnWorkers(casts.views.size(), options.num_threads, [&](std::size_t cast, int worker) {
    const std::size_t view_index = casts.views[cast];
    const TextureView& view = views[view_index];
    GeometryMaps& maps = worker_maps[static_cast<std::size_t>(worker)];
    // The maps hold every stride-th pixel: map (col, row) is the image's pixel (StridedPixel(col), StridedPixel(row)).
    const int stride = casts.stride_of_view[view_index];
    ++views_by_stride[static_cast<std::size_t>(stride)];
    const int width = static_cast<int>(view.camera.width), height = static_cast<int>(view.camera.height);
    cv::Rect window;  // of the strided table; empty: all of it
    if (casts.faces_within) {
      bool whole = false;
      window = CastWindow(view, *casts.faces_within, stride, &whole);
      if (!whole && window.empty()) {
        if (progress) progress->Advance();
        return;
      }
    }
    raycaster.RenderStrided(view, stride, &maps, window);
    // The image's pixels under the maps' rays, whose confidence is read.
    const cv::Point origin = maps.origin;
    const int image_x = StridedPixel(origin.x, stride, width), image_y = StridedPixel(origin.y, stride, height);
    const cv::Rect image_window =
        window.empty() ? cv::Rect()
                       : cv::Rect(image_x, image_y, StridedPixel(origin.x + maps.face_id.cols - 1, stride, width) - image_x + 1,
                                  StridedPixel(origin.y + maps.face_id.rows - 1, stride, height) - image_y + 1);
    const cv::Mat confidence = LoadViewConfidence(source, views, view_index, image_window);
    const cv::Point confidence_origin = image_window.empty() ? cv::Point(0, 0) : image_window.tl();
    thread_local FaceHits face_hits;
    face_hits.Resize(num_faces);
    face_hits.Clear();
    for (int row = 0; row < maps.face_id.rows; ++row) {
      const int* face_row = maps.face_id.ptr<int>(row);
      const cv::Vec3f* confidence_row =
          confidence.empty() ? nullptr
                             : confidence.ptr<cv::Vec3f>(StridedPixel(origin.y + row, stride, height) - confidence_origin.y);
      for (int col = 0; col < maps.face_id.cols; ++col) {
        const int face = face_row[col];
        if (face < 0) continue;
        if (face_hits.hits[face]++ == 0) face_hits.touched.push_back(static_cast<std::uint32_t>(face));
        const cv::Vec3f* value =
            confidence_row ? confidence_row + (StridedPixel(origin.x + col, stride, width) - confidence_origin.x) : nullptr;
        face_hits.confidence_sum[face] += value ? ((*value)[0] + (*value)[1] + (*value)[2]) / 3.0f : 1.0f;
      }
    }
    // Faces between pixel centres, next to seen faces: the centroid's pixel must see the centroid.
    const std::size_t num_hit = face_hits.touched.size();
    std::vector<std::uint32_t> subpixel;
    for (std::size_t i = 0; i < num_hit; ++i) {
      const std::uint32_t face = face_hits.touched[i];
      for (const std::uint32_t* n = adjacency.begin(face); n != adjacency.end(face); ++n) {
        if (face_hits.hits[*n] == 0) subpixel.push_back(*n);
      }
    }
    std::sort(subpixel.begin(), subpixel.end());
    subpixel.erase(std::unique(subpixel.begin(), subpixel.end()), subpixel.end());

    const Eigen::Vector3d centre_in_world = view.cam_from_world.TargetOriginInSource();
    const auto offer = [&](std::uint32_t face, bool seen_by_pixels) {
      const Mesh::Face& corners = mesh.faces[face];
      const Eigen::Vector3d& a = mesh.vertices[corners[0]];
      const Eigen::Vector3d& b = mesh.vertices[corners[1]];
      const Eigen::Vector3d& c = mesh.vertices[corners[2]];
      const Eigen::Vector3d centroid = (a + b + c) / 3.0;
      const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
      const double cos_angle = std::abs(normal.dot((centre_in_world - centroid).normalized()));
      if (!(cos_angle >= options.min_cos_angle)) return;
      std::array<Eigen::Vector2d, 3> pixels;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d point_in_cam = view.cam_from_world * mesh.vertices[corners[k]];
        if (point_in_cam.z() <= 0.0) return;
        pixels[k] = view.camera.ImgFromCam(point_in_cam);
      }
      const double area_in_pixels =
          0.5 * std::abs((pixels[1] - pixels[0]).x() * (pixels[2] - pixels[0]).y() -
                         (pixels[1] - pixels[0]).y() * (pixels[2] - pixels[0]).x());
      if (!std::isfinite(area_in_pixels)) return;
      double visible_fraction = 1.0;
      double mean_confidence = 1.0;
      if (seen_by_pixels) {
        // The rays that hit the face among those that fall inside it: 1 for a face nothing hides, however
        // the pixel grid falls on it (the hits over its area in pixels would scatter by about its
        // perimeter over its area, 20 % at 100 pixels).
        const double hits = double(face_hits.hits[face]);
        if (hits * double(stride) * double(stride) < area_in_pixels) {
          const int inside = RaysInside(pixels, stride);
          visible_fraction = inside > 0 ? std::min(1.0, hits / double(inside)) : 1.0;
        }
        mean_confidence = double(face_hits.confidence_sum[face]) / double(face_hits.hits[face]);
      } else {
        const Eigen::Vector3d centroid_in_cam = view.cam_from_world * centroid;
        const Eigen::Vector2d pixel = view.camera.ImgFromCam(centroid_in_cam);
        const int col = static_cast<int>(std::floor(pixel.x())), row = static_cast<int>(std::floor(pixel.y()));
        if (!(col >= 0 && row >= 0 && col < width && row < height)) return;
        const int map_col = col / stride - origin.x, map_row = row / stride - origin.y;
        if (!(map_col >= 0 && map_row >= 0 && map_col < maps.depth.cols && map_row < maps.depth.rows)) return;
        const float depth = maps.depth.at<float>(map_row, map_col);
        if (!(std::abs(depth - centroid_in_cam.z()) <= 0.01 * centroid_in_cam.z())) return;
        const int confidence_col = col - confidence_origin.x, confidence_row = row - confidence_origin.y;
        if (!confidence.empty() && confidence_col >= 0 && confidence_row >= 0 && confidence_col < confidence.cols &&
            confidence_row < confidence.rows) {
          const cv::Vec3f& value = confidence.at<cv::Vec3f>(confidence_row, confidence_col);
          mean_confidence = (value[0] + value[1] + value[2]) / 3.0;
        }
      }
      const double quality = area_in_pixels * visible_fraction * mean_confidence;
      if (!(quality > 0.0)) return;
      std::lock_guard<std::mutex> lock(locks[face % kNumLocks]);
      candidates.Offer(face, {static_cast<std::uint32_t>(view_index), static_cast<float>(quality)});
    };
    for (std::size_t i = 0; i < num_hit; ++i) offer(face_hits.touched[i], true);
    for (std::uint32_t face : subpixel) offer(face, false);
    if (progress) progress->Advance();
  });
  if (!progress) return candidates;
  progress->Finish();
  std::string strides;
  for (std::size_t stride = 1; stride < views_by_stride.size(); ++stride) {
    if (views_by_stride[stride] == 0) continue;
    strides += (strides.empty() ? "" : ", ") + std::to_string(views_by_stride[stride].load()) +
               (stride == 1 ? std::string(" view(s) at every pixel")
                               : " at every " + std::string(kOrdinals[stride]) + " pixel in each direction");
  }
  LogInfo() << "texture: visibility cast " << strides << " (face_view_candidates.h)";
  return candidates;
}

}  // namespace lutex
