#include "tests/support/charuco_board.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "lib/image/image_io.h"

namespace lutex::testing {

CharucoSpec PatchedCharucoSpec(double square) {
  CharucoSpec spec;
  spec.squares_x = 6;
  spec.squares_y = 4;
  spec.square_size = square;
  spec.marker_size = 0.75 * square;
  spec.black_albedo = Eigen::Vector3d::Constant(SrgbToLinear(25 / 255.0));
  const std::vector<std::pair<Eigen::Vector3d, double>> colours = {
      {Eigen::Vector3d(0.60, 0.05, 0.04), 4.17},  {Eigen::Vector3d(0.06, 0.45, 0.08), 4.17},
      {Eigen::Vector3d(0.05, 0.10, 0.55), 4.17},  {Eigen::Vector3d(0.70, 0.60, 0.10), -1.75},
      {Eigen::Vector3d(0.08, 0.50, 0.55), -1.75}, {Eigen::Vector3d(0.35, 0.35, 0.35), -1.75}};
  for (std::size_t p = 0; p < colours.size(); ++p) {
    ColourPatch patch;
    patch.name = "patch " + std::to_string(p);
    const double x0 = (0.25 + 2.0 * static_cast<double>(p % 3)) * square, y0 = colours[p].second * square;
    patch.min_in_board = Eigen::Vector2d(x0, y0);
    patch.max_in_board = Eigen::Vector2d(x0 + 1.5 * square, y0 + 1.5 * square);
    patch.albedo = colours[p].first;
    spec.patches.push_back(patch);
  }
  return spec;
}

Mesh CharucoBoardMesh(const CharucoSpec& spec) {
  const CharucoLayout layout = CharucoBoardLayout(spec);
  const double square = spec.square_size, cell = square / 8;
  const Eigen::Vector3d white = Eigen::Vector3d::Constant(SrgbToLinear(230 / 255.0));
  Mesh mesh;
  for (int b = -20; b < 8 * spec.squares_y + 20; ++b) {
    for (int a = -8; a < 8 * (spec.squares_x + 1); ++a) {
      const Eigen::Vector2d centre((a + 0.5) * cell, (b + 0.5) * cell);
      Eigen::Vector3d albedo = white;
      const int i = static_cast<int>(std::floor(centre.x() / square)), j = static_cast<int>(std::floor(centre.y() / square));
      if (i >= 0 && j >= 0 && i < spec.squares_x && j < spec.squares_y &&
          layout.black[static_cast<std::size_t>(j * spec.squares_x + i)]) {
        albedo = spec.black_albedo;
      }
      for (std::size_t m = 0; m < layout.marker_corners.size(); ++m) {
        const auto& c = layout.marker_corners[m];
        const Eigen::Vector2d across = c[1] - c[0], down = c[3] - c[0];
        const double u = (centre - c[0]).dot(across) / across.squaredNorm();
        const double v = (centre - c[0]).dot(down) / down.squaredNorm();
        if (u < 0 || v < 0 || u >= 1 || v >= 1) continue;
        int n = 0;
        const std::vector<bool> bits = CharucoMarkerBits(spec, layout.marker_ids[m], &n);
        albedo = bits[static_cast<std::size_t>(static_cast<int>(v * n) * n + static_cast<int>(u * n))] ? white
                                                                                                    : spec.black_albedo;
      }
      for (const ColourPatch& patch : spec.patches) {
        if ((centre - patch.min_in_board).minCoeff() > 0 && (patch.max_in_board - centre).minCoeff() > 0) albedo = patch.albedo;
      }
      const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
      const double x = a * cell, y = b * cell;
      mesh.vertices.insert(mesh.vertices.end(), {Eigen::Vector3d(x, y, 0), Eigen::Vector3d(x + cell, y, 0),
                                                 Eigen::Vector3d(x + cell, y + cell, 0), Eigen::Vector3d(x, y + cell, 0)});
      mesh.faces.push_back({base, base + 1, base + 2});
      mesh.faces.push_back({base, base + 2, base + 3});
      Eigen::Matrix<std::uint8_t, 3, 1> encoded;
      for (int k = 0; k < 3; ++k) encoded[k] = static_cast<std::uint8_t>(std::lround(255.0 * LinearToSrgb(albedo[k])));
      mesh.face_colors.push_back(encoded);
      mesh.face_colors.push_back(encoded);
    }
  }
  return mesh;
}

}  // namespace lutex::testing
