#include "lib/geometry/sparse_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <opencv2/imgproc.hpp>

#include "lib/util/logging.h"
#include "lib/util/median.h"

namespace lutex {

namespace {

constexpr int kMaxGridSide = 8192;

struct LevelPoint {
  Eigen::Vector3d xyz;  // in the level frame: +z is up
  bool kept = true;
};

// The grid: node (i, j) at (x0 + i res, y0 + j res) of the level frame.
struct Grid {
  double x0 = 0.0, y0 = 0.0, res = 1.0;
  int width = 0, height = 0;
  Eigen::Vector2d Node(double x, double y) const { return {(x - x0) / res, (y - y0) / res}; }
};

// The image's footprint on the plane z = `height` of the level frame, as (x, y) corners; empty when a
// corner ray does not reach the plane (an image looking at the horizon).
std::vector<Eigen::Vector2d> Footprint(const Camera& camera, const Rigid3d& cam_from_world,
                                       const Eigen::Quaterniond& level_from_model, double height) {
  const Eigen::Quaterniond level_from_cam = level_from_model * cam_from_world.rotation.inverse();
  const Eigen::Vector3d centre = level_from_model * cam_from_world.TargetOriginInSource();
  std::vector<Eigen::Vector2d> corners;
  const double w = double(camera.width), h = double(camera.height);
  for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(w, h),
                                       Eigen::Vector2d(0, h)}) {
    const Eigen::Vector3d ray = level_from_cam * camera.CamFromImg(pixel);
    const double t = (height - centre.z()) / ray.z();
    if (!(t > 0.0) || !std::isfinite(t)) return {};
    corners.push_back((centre + t * ray).head<2>());
  }
  return corners;
}

// Least-squares plane z = a x + b y + c through `points`; the residual of each.
std::vector<double> PlaneResiduals(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d row(p.x() - mean.x(), p.y() - mean.y(), 1.0);
    normal += row * row.transpose();
    rhs += row * (p.z() - mean.z());
  }
  const Eigen::Vector3d plane = normal.ldlt().solve(rhs);
  std::vector<double> residuals;
  for (const auto& p : points) {
    residuals.push_back(p.z() - mean.z() - plane.x() * (p.x() - mean.x()) - plane.y() * (p.y() - mean.y()) - plane.z());
  }
  return residuals;
}

}  // namespace

void SparseSurfaceOptions::Check() const {
  if (!(resolution >= 0.0) || !std::isfinite(resolution)) throw std::invalid_argument("the resolution must be >= 0");
  if (min_track_length < 2) throw std::invalid_argument("the minimum track length must be at least 2");
  if (!(max_reprojection_error > 0.0)) throw std::invalid_argument("the largest reprojection error must be positive");
  if (!(outlier_mads > 0.0)) throw std::invalid_argument("the outlier threshold must be positive");
  if (!(smoothness > 0.0) || !std::isfinite(smoothness)) throw std::invalid_argument("the smoothness must be positive");
}

namespace {

// Steps 2 to 5 on points in the level frame; `heights_of_image`: the heights of the points each image
// sees, for its footprint. `surface` comes with the counts of step 1.
SparseSurface FitSurface(std::vector<LevelPoint> points, std::map<std::uint32_t, std::vector<double>> heights_of_image,
                         const SparseModel& model, const Eigen::Quaterniond& level_from_model,
                         const SparseSurfaceOptions& options, SparseSurface surface) {
  SparseSurfaceSummary& summary = surface.summary;
  // The points must span an area, not a line.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p.xyz.head<2>();
  mean /= double(points.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const auto& p : points) covariance += (p.xyz.head<2>() - mean) * (p.xyz.head<2>() - mean).transpose();
  covariance /= double(points.size());
  const Eigen::Vector2d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance).eigenvalues();
  if (!(spread.x() > 1e-6 * spread.y()) || !(spread.y() > 0.0)) {
    throw std::invalid_argument("the model's 3-D points lie on a line (seen from above): they span no surface");
  }

  // 2. The footprints, and the grid over them and the points: the points' extent is taken between their
  // 0.5th and 99.5th percentiles (a few points far away do not stretch the grid), and a footprint reaches
  // at most half that extent beyond it (images looking far to the side add no terrain to fit).
  std::vector<double> xs, ys;
  for (const auto& p : points) {
    xs.push_back(p.xyz.x());
    ys.push_back(p.xyz.y());
  }
  const auto percentile = [](std::vector<double>& values, double fraction) {
    const auto at = values.begin() + static_cast<std::ptrdiff_t>(fraction * double(values.size() - 1));
    std::nth_element(values.begin(), at, values.end());
    return *at;
  };
  const Eigen::Vector2d low(percentile(xs, 0.005), percentile(ys, 0.005));
  const Eigen::Vector2d high(percentile(xs, 0.995), percentile(ys, 0.995));
  std::vector<std::vector<Eigen::Vector2d>> footprints;
  for (auto& [image_id, heights] : heights_of_image) {
    const auto image = model.images.find(image_id);
    if (image == model.images.end() || heights.size() < 3) continue;
    const auto camera = model.cameras.find(image->second.camera_id);
    if (camera == model.cameras.end()) continue;
    std::vector<Eigen::Vector2d> corners =
        Footprint(camera->second, image->second.cam_from_world, level_from_model, MedianInPlace(heights));
    if (!corners.empty()) footprints.push_back(std::move(corners));
  }
  if (footprints.empty()) throw std::invalid_argument("no image's view reaches the ground its points lie on");
  const Eigen::Vector2d margin = 0.5 * (high - low);
  Eigen::Vector2d grid_low = Eigen::Vector2d::Constant(HUGE_VAL), grid_high = -grid_low;
  for (const auto& corners : footprints) {
    for (const auto& corner : corners) {
      grid_low = grid_low.cwiseMin(corner.cwiseMax(low - margin));
      grid_high = grid_high.cwiseMax(corner.cwiseMin(high + margin));
    }
  }
  std::size_t inside = 0;
  for (const auto& p : points) {
    inside += (p.xyz.head<2>().array() >= low.array()).all() && (p.xyz.head<2>().array() <= high.array()).all();
  }
  const double area = std::max((high - low).prod(), 1e-12);
  double resolution =
      options.resolution > 0.0 ? options.resolution : std::sqrt(area / double(std::max<std::size_t>(inside, 1)));
  resolution = std::max(resolution, (grid_high - grid_low).maxCoeff() / (kMaxGridSide - 1));
  Grid grid;
  grid.res = resolution;
  grid.x0 = grid_low.x();
  grid.y0 = grid_low.y();
  grid.width = static_cast<int>(std::ceil((grid_high.x() - grid_low.x()) / resolution)) + 1;
  grid.height = static_cast<int>(std::ceil((grid_high.y() - grid_low.y()) / resolution)) + 1;
  summary.resolution = resolution;
  summary.grid_width = grid.width;
  summary.grid_height = grid.height;
  cv::Mat footprint(grid.height, grid.width, CV_8UC1, cv::Scalar(0));
  constexpr int kShift = 4;  // sub-node precision of the polygons
  for (const auto& corners : footprints) {
    std::vector<cv::Point> polygon;
    for (const auto& corner : corners) {
      // Corners of rays near the horizon lie far away: kept within a cell of the grid (fixed point must
      // not overflow), the polygon still covers the grid where the footprint does.
      const Eigen::Vector2d near = corner.cwiseMax(grid_low - Eigen::Vector2d::Constant(resolution))
                                       .cwiseMin(grid_high + Eigen::Vector2d::Constant(resolution));
      const Eigen::Vector2d node = grid.Node(near.x(), near.y()) * double(1 << kShift);
      polygon.emplace_back(static_cast<int>(std::lround(node.x())), static_cast<int>(std::lround(node.y())));
    }
    cv::fillConvexPoly(footprint, polygon, cv::Scalar(255), cv::LINE_8, kShift);
  }
  const auto node_of = [&](const Eigen::Vector3d& xyz) {
    const Eigen::Vector2d node = grid.Node(xyz.x(), xyz.y());
    return cv::Point(static_cast<int>(std::lround(node.x())), static_cast<int>(std::lround(node.y())));
  };
  for (auto& p : points) {
    const cv::Point node = node_of(p.xyz);
    if (node.x < 0 || node.y < 0 || node.x >= grid.width || node.y >= grid.height || !footprint.at<uchar>(node)) {
      p.kept = false;
      ++summary.outside_footprint;
    }
  }

  // 3. Outliers against the local plane of the points in their 3 x 3 bins, bins of twice the points' mean
  // spacing (about 36 points each way), whatever the grid's resolution.
  const double spacing = std::sqrt(area / double(std::max<std::size_t>(inside, 1)));
  const double bin = std::max(resolution, 2.0 * spacing);
  const int bins_x = static_cast<int>(std::ceil((grid_high.x() - grid_low.x()) / bin)) + 1;
  const int bins_y = static_cast<int>(std::ceil((grid_high.y() - grid_low.y()) / bin)) + 1;
  const auto bin_of = [&](const Eigen::Vector3d& xyz) {
    return cv::Point(std::clamp(static_cast<int>(std::floor((xyz.x() - grid.x0) / bin)), 0, bins_x - 1),
                     std::clamp(static_cast<int>(std::floor((xyz.y() - grid.y0) / bin)), 0, bins_y - 1));
  };
  std::vector<std::vector<std::size_t>> points_of_bin(static_cast<std::size_t>(bins_x) * bins_y);
  const auto bin_index = [&](const cv::Point& b) { return static_cast<std::size_t>(b.y) * bins_x + b.x; };
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].kept) points_of_bin[bin_index(bin_of(points[i].xyz))].push_back(i);
  }
  std::vector<bool> outlier(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].kept) continue;
    const cv::Point centre = bin_of(points[i].xyz);
    std::vector<Eigen::Vector3d> neighbourhood{points[i].xyz};
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point other(centre.x + dx, centre.y + dy);
        if (other.x < 0 || other.y < 0 || other.x >= bins_x || other.y >= bins_y) continue;
        for (std::size_t j : points_of_bin[bin_index(other)]) {
          if (j != i) neighbourhood.push_back(points[j].xyz);
        }
      }
    }
    if (neighbourhood.size() < 6) continue;
    std::vector<double> residuals = PlaneResiduals(neighbourhood);
    const double own = std::abs(residuals[0]);
    for (double& r : residuals) r = std::abs(r);
    const double deviation = 1.4826 * MedianInPlace(residuals);
    if (own > options.outlier_mads * std::max(deviation, 0.25 * resolution)) outlier[i] = true;
  }
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].kept) continue;
    if (outlier[i]) {
      ++summary.outliers;
      continue;
    }
    kept.push_back(points[i].xyz);
  }
  summary.kept_points = kept.size();
  if (kept.size() < 10) throw std::invalid_argument("too few 3-D points under the images for a surface");

  // 4. Heights on the footprint's nodes: bilinear data terms and second differences.
  std::vector<int> unknown(static_cast<std::size_t>(grid.width) * grid.height, -1);
  int num_unknowns = 0;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      if (footprint.at<uchar>(y, x)) unknown[static_cast<std::size_t>(y) * grid.width + x] = num_unknowns++;
    }
  }
  summary.footprint_cells = static_cast<std::size_t>(num_unknowns);
  const auto index = [&](int x, int y) {
    return (x < 0 || y < 0 || x >= grid.width || y >= grid.height) ? -1 : unknown[static_cast<std::size_t>(y) * grid.width + x];
  };
  std::vector<double> kept_heights;
  for (const auto& p : kept) kept_heights.push_back(p.z());
  const double median_height = MedianInPlace(kept_heights);
  // Smoothness per node, relative to the data a node gets on average.
  const double lambda = options.smoothness * std::max(1.0, double(kept.size()) / double(num_unknowns));
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs_rows;
  int row = 0;
  std::vector<bool> has_data(static_cast<std::size_t>(num_unknowns), false);
  for (const auto& p : kept) {
    const Eigen::Vector2d node = grid.Node(p.x(), p.y());
    const int x = static_cast<int>(std::floor(node.x())), y = static_cast<int>(std::floor(node.y()));
    const double fx = node.x() - x, fy = node.y() - y;
    const int corners[4] = {index(x, y), index(x + 1, y), index(x, y + 1), index(x + 1, y + 1)};
    const double weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    if (std::all_of(std::begin(corners), std::end(corners), [](int c) { return c >= 0; })) {
      for (int k = 0; k < 4; ++k) triplets.emplace_back(row, corners[k], weights[k]);
      for (int k = 0; k < 4; ++k) has_data[static_cast<std::size_t>(corners[k])] = true;
    } else {
      const int nearest = index(static_cast<int>(std::lround(node.x())), static_cast<int>(std::lround(node.y())));
      if (nearest < 0) continue;
      triplets.emplace_back(row, nearest, 1.0);
      has_data[static_cast<std::size_t>(nearest)] = true;
    }
    rhs_rows.push_back(p.z());
    ++row;
  }
  const double bend = std::sqrt(lambda), stretch = std::sqrt(1e-3 * lambda), anchor = std::sqrt(1e-6 * lambda);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const int centre = index(x, y);
      if (centre < 0) continue;
      for (const auto& [dx, dy] : {std::pair<int, int>(1, 0), std::pair<int, int>(0, 1)}) {
        const int before = index(x - dx, y - dy), after = index(x + dx, y + dy);
        if (before >= 0 && after >= 0) {
          triplets.emplace_back(row, before, bend);
          triplets.emplace_back(row, centre, -2.0 * bend);
          triplets.emplace_back(row, after, bend);
          rhs_rows.push_back(0.0);
          ++row;
        }
        if (after >= 0) {
          triplets.emplace_back(row, centre, stretch);
          triplets.emplace_back(row, after, -stretch);
          rhs_rows.push_back(0.0);
          ++row;
        }
      }
      // A faint pull to the median height keeps parts of the footprint without points solvable.
      triplets.emplace_back(row, centre, anchor);
      rhs_rows.push_back(anchor * median_height);
      ++row;
    }
  }
  Eigen::SparseMatrix<double> design(row, num_unknowns);
  design.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::Map<const Eigen::VectorXd> targets(rhs_rows.data(), row);
  const Eigen::SparseMatrix<double> normal = design.transpose() * design;
  const Eigen::VectorXd rhs = design.transpose() * targets;
  // Conjugate gradients, memory linear in the nodes (a direct factorisation's fill-in doubles its memory
  // with the grid: 1.3 GiB at 0.8 M faces). The bending term makes the system stiff, so a large grid takes
  // thousands of iterations (~10 per node along the grid's sides).
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver;
  solver.setTolerance(1e-6);  // relative residual: heights to well under the points' noise
  solver.setMaxIterations(std::max(2000, 10 * (grid.width + grid.height)));
  solver.compute(normal);
  const Eigen::VectorXd heights = solver.solveWithGuess(rhs, Eigen::VectorXd::Constant(num_unknowns, median_height));
  if (!heights.allFinite()) throw std::runtime_error("the surface fit did not converge");
  if (solver.info() != Eigen::Success) {
    LogWarning() << "mesh: the height field's solve stopped after " << solver.iterations()
                 << " iterations at relative error " << solver.error()
                 << " (holes far from the points may be filled flatter than smooth)";
  }

  // Residuals and the 2.5-D check.
  const auto height_at = [&](double px, double py) {
    const Eigen::Vector2d node = grid.Node(px, py);
    const int c = index(static_cast<int>(std::lround(node.x())), static_cast<int>(std::lround(node.y())));
    return c >= 0 ? heights[c] : std::numeric_limits<double>::quiet_NaN();
  };
  double squares = 0.0;
  std::size_t counted = 0;
  std::vector<int> above(static_cast<std::size_t>(num_unknowns), 0), below(static_cast<std::size_t>(num_unknowns), 0);
  for (const auto& p : kept) {
    const double h = height_at(p.x(), p.y());
    if (!std::isfinite(h)) continue;
    squares += (p.z() - h) * (p.z() - h);
    ++counted;
    const cv::Point node = node_of(p);
    const int c = index(node.x, node.y);
    if (c < 0) continue;
    if (p.z() - h > 2.0 * resolution) ++above[static_cast<std::size_t>(c)];
    if (p.z() - h < -2.0 * resolution) ++below[static_cast<std::size_t>(c)];
  }
  summary.rms_residual = counted ? std::sqrt(squares / double(counted)) : 0.0;
  const double steep = std::tan(60.0 * M_PI / 180.0);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const int c = index(x, y);
      if (c < 0) continue;
      summary.cells_with_points += has_data[static_cast<std::size_t>(c)];
      if (above[static_cast<std::size_t>(c)] > 0 && below[static_cast<std::size_t>(c)] > 0) ++summary.layered_cells;
      const int l = index(x - 1, y), r = index(x + 1, y), d = index(x, y - 1), u = index(x, y + 1);
      if (l < 0 || r < 0 || d < 0 || u < 0) continue;
      const double gx = (heights[r] - heights[l]) / (2.0 * resolution), gy = (heights[u] - heights[d]) / (2.0 * resolution);
      if (std::hypot(gx, gy) > steep) ++summary.steep_cells;
    }
  }

  // 5. The mesh, in the model's frame.
  const Eigen::Quaterniond model_from_level = level_from_model.inverse();
  Mesh& mesh = surface.mesh;
  mesh.vertices.resize(static_cast<std::size_t>(num_unknowns));
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const int c = index(x, y);
      if (c >= 0) {
        mesh.vertices[static_cast<std::size_t>(c)] =
            model_from_level * Eigen::Vector3d(grid.x0 + x * resolution, grid.y0 + y * resolution, heights[c]);
      }
    }
  }
  for (int y = 0; y + 1 < grid.height; ++y) {
    for (int x = 0; x + 1 < grid.width; ++x) {
      const int a = index(x, y), b = index(x + 1, y), c = index(x + 1, y + 1), d = index(x, y + 1);
      if (a < 0 || b < 0 || c < 0 || d < 0) continue;
      mesh.faces.push_back({std::uint32_t(a), std::uint32_t(b), std::uint32_t(c)});
      mesh.faces.push_back({std::uint32_t(a), std::uint32_t(c), std::uint32_t(d)});
    }
  }
  if (mesh.faces.empty()) throw std::invalid_argument("the images' footprints leave no surface to mesh");
  // Nodes of no square are not part of the surface.
  std::vector<int> remap(mesh.vertices.size(), -1);
  std::vector<Eigen::Vector3d> used;
  for (Mesh::Face& face : mesh.faces) {
    for (std::uint32_t& v : face) {
      if (remap[v] < 0) {
        remap[v] = static_cast<int>(used.size());
        used.push_back(mesh.vertices[v]);
      }
      v = static_cast<std::uint32_t>(remap[v]);
    }
  }
  mesh.vertices = std::move(used);
  summary.num_vertices = mesh.vertices.size();
  summary.num_faces = mesh.faces.size();
  return surface;
}


}  // namespace

SparseSurface SurfaceFromSparsePoints(const SparseModel& model, const Eigen::Vector3d& up_in_model,
                                      const SparseSurfaceOptions& options) {
  options.Check();
  SparseSurface surface;
  SparseSurfaceSummary& summary = surface.summary;
  summary.num_points = model.points3D.size();
  if (model.points3D.empty()) throw std::invalid_argument("the model has no 3-D points (points3D is empty)");
  const Eigen::Quaterniond level_from_model = Eigen::Quaterniond::FromTwoVectors(up_in_model.normalized(), Eigen::Vector3d::UnitZ());

  // 1. Points seen often and well; each image's heights, for its footprint.
  std::vector<LevelPoint> points;
  std::map<std::uint32_t, std::vector<double>> heights_of_image;
  for (const auto& [id, point] : model.points3D) {
    if (static_cast<int>(point.track.size()) < options.min_track_length) {
      ++summary.short_tracks;
      continue;
    }
    if (!(point.error <= options.max_reprojection_error)) {
      ++summary.large_errors;
      continue;
    }
    const Eigen::Vector3d xyz = level_from_model * point.xyz;
    if (!xyz.allFinite()) continue;
    points.push_back({xyz, true});
    for (const TrackElement& element : point.track) heights_of_image[element.image_id].push_back(xyz.z());
  }
  if (points.size() < 10) {
    throw std::invalid_argument("only " + std::to_string(points.size()) + " of the model's " +
                                std::to_string(summary.num_points) + " 3-D points are seen in " +
                                std::to_string(options.min_track_length) + " or more images with a reprojection error "
                                "of at most " + std::to_string(options.max_reprojection_error) + " px: too few for a surface");
  }
  return FitSurface(std::move(points), std::move(heights_of_image), model, level_from_model, options, std::move(surface));
}

SparseSurface SurfaceFromPointCloud(const std::vector<Eigen::Vector3d>& points_in_model, const SparseModel& model,
                                    const Eigen::Vector3d& up_in_model, const SparseSurfaceOptions& options) {
  options.Check();
  SparseSurface surface;
  surface.summary.num_points = points_in_model.size();
  if (points_in_model.size() < 10) {
    throw std::invalid_argument("the point cloud has " + std::to_string(points_in_model.size()) +
                                " points: too few for a surface");
  }
  const Eigen::Quaterniond level_from_model = Eigen::Quaterniond::FromTwoVectors(up_in_model.normalized(), Eigen::Vector3d::UnitZ());
  std::vector<LevelPoint> points;
  std::vector<double> heights;
  for (const Eigen::Vector3d& point : points_in_model) {
    const Eigen::Vector3d xyz = level_from_model * point;
    if (!xyz.allFinite()) continue;
    points.push_back({xyz, true});
    heights.push_back(xyz.z());
  }
  // A fused cloud keeps no tracks: every image's footprint is cut at the cloud's median height.
  const double median = MedianInPlace(heights);
  std::map<std::uint32_t, std::vector<double>> heights_of_image;
  for (const auto& [id, image] : model.images) heights_of_image[id] = {median, median, median};
  return FitSurface(std::move(points), std::move(heights_of_image), model, level_from_model, options, std::move(surface));
}

}  // namespace lutex
