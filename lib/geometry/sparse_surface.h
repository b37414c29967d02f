#pragma once

// A 2.5-D surface from a sparse COLMAP model, for machines without a GPU (COLMAP's dense stereo needs
// CUDA): seafloor surveys are mostly a terrain seen from above, and a sparse model of a survey holds
// thousands of points per image, enough for a surface that gives the LUT its depth and the texture a
// surface to lie on.
//
//   1. Points: those seen in at least `min_track_length` images with a reprojection error of at most
//      `max_reprojection_error` pixels, in a frame whose +z is the model's up.
//   2. Footprint: the union of the images' footprints, each the image's frustum cut by the plane at the
//      median height of the points it sees, on a grid of `resolution` (default: the mean spacing of the
//      points). Points outside every footprint are dropped.
//   3. Outliers: each point against a least-squares plane through the points of its 3 x 3 bins (bins of
//      twice the mean spacing of the points); points further than `outlier_mads` robust deviations (at
//      least a quarter cell) are dropped.
//   4. Heights: a regularised fit on the grid's nodes (bilinear data terms, one per point, plus
//      `smoothness` x second differences along x and y per node, solved with conjugate gradients): holes
//      are filled smoothly within the footprint, nothing outside it.
//   5. Mesh: two triangles per grid square whose four nodes lie in the footprint, in the model's frame.
//
// The 2.5-D assumption is checked: the summary counts the footprint cells where the fitted surface is
// steeper than 60 degrees, or where points lie both well above and well below it (walls, overhangs that
// a height field smooths over).

#include <cstddef>
#include <string>

#include <Eigen/Core>

#include "lib/geometry/mesh.h"
#include "lib/geometry/sparse_model.h"

namespace lutex {

struct SparseSurfaceOptions {
  double resolution = 0.0;  // grid cell in model units; 0: from the point density
  int min_track_length = 3;
  double max_reprojection_error = 2.0;  // pixels
  double outlier_mads = 4.0;
  double smoothness = 1.0;
  void Check() const;
};

struct SparseSurfaceSummary {
  std::size_t num_points = 0;
  std::size_t short_tracks = 0;      // dropped: seen in too few images
  std::size_t large_errors = 0;      // dropped: reprojection error too large
  std::size_t outside_footprint = 0; // dropped: under no image
  std::size_t outliers = 0;          // dropped: off the local surface
  std::size_t kept_points = 0;
  double resolution = 0.0;
  int grid_width = 0, grid_height = 0;
  std::size_t footprint_cells = 0;
  std::size_t cells_with_points = 0;
  std::size_t steep_cells = 0;    // fitted slope above 60 degrees
  std::size_t layered_cells = 0;  // points well above and well below the surface
  double rms_residual = 0.0;      // of the kept points against the surface, model units
  std::size_t num_vertices = 0, num_faces = 0;
};

struct SparseSurface {
  Mesh mesh;  // in the model's frame
  SparseSurfaceSummary summary;
};

// `up_in_model`: the model's up (unit). Throws std::invalid_argument when the model has no 3-D points,
// too few survive the filters (fewer than 10) or they do not span an area (all on a line).
SparseSurface SurfaceFromSparsePoints(const SparseModel& model, const Eigen::Vector3d& up_in_model,
                                      const SparseSurfaceOptions& options);

// The same from a dense point cloud (COLMAP's fused.ply), which keeps no tracks: steps 2 to 5, every
// image's footprint cut at the cloud's median height. `model` gives the images' footprints.
SparseSurface SurfaceFromPointCloud(const std::vector<Eigen::Vector3d>& points_in_model, const SparseModel& model,
                                    const Eigen::Vector3d& up_in_model, const SparseSurfaceOptions& options);

}  // namespace lutex
