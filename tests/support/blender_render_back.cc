#include "tests/support/blender_render_back.h"

#include <cmath>

#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex::testing {

namespace fs = std::filesystem;

TexturedMesh ReadTexturedPly(const fs::path& ply) {
  TexturedMesh textured;
  textured.mesh = ReadMesh(ply);
  fs::path page = ply.parent_path() / (ply.stem().string() + "_texture.png");
  textured.pages.push_back(ReadLinearImage(page, ImageEncoding::kLinear16));
  const float width = float(textured.pages[0].cols), height = float(textured.pages[0].rows);
  for (const auto& corners : textured.mesh.corner_texcoords) {
    const bool textured_face = !(corners[0].isZero() && corners[1].isZero() && corners[2].isZero());
    textured.face_page.push_back(textured_face ? 0 : -1);
    std::array<Eigen::Vector2f, 3> texels;
    for (int k = 0; k < 3; ++k) texels[k] = Eigen::Vector2f(corners[k].x() * width, (1.0f - corners[k].y()) * height);
    textured.face_corner_texels.push_back(texels);
  }
  return textured;
}

RenderBack CompareWithGroundTruth(const fs::path& dataset, const TexturedMesh& textured) {
  const SparseModel model = ReadSparseModel(dataset / "sparse" / "0");
  const RaycastScene scene(textured.mesh);
  const CameraRays rays(model.cameras.begin()->second);
  GeometryMapsOptions options;
  options.barycentrics = true;
  double sum = 0.0;
  std::size_t samples = 0, surface = 0, seen = 0;
  for (const auto& [id, image] : model.images) {
    const cv::Mat truth = ReadLinearImage(dataset / "gt" / "albedo" / (fs::path(image.name).stem().string() + ".exr"),
                                          ImageEncoding::kFloat);
    const GeometryMaps maps = scene.Render(rays, image.cam_from_world, options);
    for (int row = 0; row < truth.rows; ++row) {
      for (int col = 0; col < truth.cols; ++col) {
        const int face = maps.face_id.at<int>(row, col);
        const cv::Vec3f expected = truth.at<cv::Vec3f>(row, col);
        if (face < 0 || expected == cv::Vec3f(0, 0, 0)) continue;
        ++surface;
        if (textured.face_page[face] < 0) continue;
        ++seen;
        const cv::Vec2f b = maps.barycentrics.at<cv::Vec2f>(row, col);
        const Eigen::Vector3f albedo = textured.AlbedoAt(face, b[0], b[1]);
        for (int c = 0; c < 3; ++c) sum += std::abs(albedo[c] - expected[c]);
        samples += 3;
      }
    }
  }
  return {100.0 * sum / double(samples), double(seen) / double(surface)};
}

}  // namespace lutex::testing
