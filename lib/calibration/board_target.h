#pragma once

// What every planar calibration board shares (chessboard_target.h, charuco_target.h): its pose from image
// points of known board coordinates, and the rays of an image meeting its plane. No COLMAP model and no
// mesh are needed: only the camera.
//
// Board frame: the board lies in z = 0, x and y along its rows and columns (metres); each board type says
// where its origin is.

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct BoardView {
  Rigid3d cam_from_board;
  double reprojection_rms = 0.0;  // pixels, of the detected points under the pose
};

// The pose from at least 4 detected points: `pixels` in the camera's convention (pixel centres at +0.5),
// undistorted with the camera (any COLMAP model), then solvePnP (IPPE, for planar points), once more
// without points off by more than 3 x the median reprojection error and 1 px. Nothing when there are too
// few points or the solve fails. reprojection_rms is over the points kept.
std::optional<BoardView> PoseFromBoardPoints(const std::vector<Eigen::Vector3d>& points_in_board,
                                             const std::vector<Eigen::Vector2d>& pixels, const Camera& camera);

// What a board gives one image: depth and normals where rays meet the board (NaN elsewhere), and the
// known albedo (linear RGB CV_32FC3) where the board's colour is known, NaN elsewhere.
struct BoardMaps {
  GeometryMaps maps;
  cv::Mat known_albedo;
};

// Where the rays of `rays` meet the board plane in front of the camera, within `min_in_board` ..
// `max_in_board` (x, y in the board frame): depth and normals (facing the camera) as the ray caster gives
// them, and the board coordinates of every hit (CV_32FC2); NaN elsewhere.
struct BoardPlaneMaps {
  GeometryMaps maps;
  cv::Mat point_in_board;
};
BoardPlaneMaps RenderBoardPlane(const BoardView& view, const CameraRays& rays, const Eigen::Vector2d& min_in_board,
                                const Eigen::Vector2d& max_in_board);

}  // namespace lutex
