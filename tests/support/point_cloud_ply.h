#pragma once

// Reads the vertex positions of a binary little-endian or ascii PLY point cloud (such as COLMAP's
// fused.ply), whatever other float/uchar properties the vertices carry. For tests of peer output.

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace lutex::testing {

std::vector<Eigen::Vector3d> ReadPlyPointPositions(const std::filesystem::path& path);

}  // namespace lutex::testing
