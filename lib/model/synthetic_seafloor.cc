#include "lib/model/synthetic_seafloor.h"

#include <cmath>
#include <random>

#include "lib/geometry/mesh_primitives.h"

namespace lutex {
namespace {

// A colour per patch from an integer hash, in a natural seafloor-ish but varied palette.
Eigen::Matrix<std::uint8_t, 3, 1> PatchColour(long px, long py, std::uint32_t seed) {
  std::uint64_t h = static_cast<std::uint64_t>(px) * 0x9E3779B1ull ^ static_cast<std::uint64_t>(py) * 0x85EBCA77ull ^
                    static_cast<std::uint64_t>(seed) * 0xC2B2AE3Dull;
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  Eigen::Matrix<std::uint8_t, 3, 1> colour;
  for (int c = 0; c < 3; ++c) colour[c] = static_cast<std::uint8_t>(40 + ((h >> (8 * c)) & 0xFF) * 190 / 255);
  return colour;
}

}  // namespace

Mesh MakeSyntheticSeafloor(const SyntheticSeafloorOptions& options) {
  const double relief = options.relief;
  Mesh seafloor = MakeHeightFieldMesh(
      [relief](double x, double y) { return relief * std::sin(0.9 * x) * std::cos(0.7 * y) + relief / 3 * std::sin(3.1 * x + 1.3 * y); },
      -options.size_x / 2, options.size_x / 2, -options.size_y / 2, options.size_y / 2,
      static_cast<int>(std::lround(options.size_x / options.cell_size)),
      static_cast<int>(std::lround(options.size_y / options.cell_size)));
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> x(-0.35 * options.size_x, 0.35 * options.size_x);
  std::uniform_real_distribution<double> y(-0.35 * options.size_y, 0.35 * options.size_y);
  std::uniform_real_distribution<double> radius(0.3, 0.6);
  for (int b = 0; b < options.num_boulders; ++b) {
    const double r = radius(random);
    AppendMesh(MakeSphereMesh(Eigen::Vector3d(x(random), y(random), -0.3 * r), r, 24, 48), &seafloor);
  }
  seafloor.vertex_texcoords.clear();
  for (const Eigen::Vector3d& v : seafloor.vertices) {
    seafloor.vertex_colors.push_back(PatchColour(std::lround(std::floor(v.x() / options.patch_size)),
                                                 std::lround(std::floor(v.y() / options.patch_size)), options.seed));
  }
  return seafloor;
}

}  // namespace lutex
