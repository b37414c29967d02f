// Writes the bundled example: a small synthetic dive as a COLMAP workspace that lutex can work on.
//
//   make_example_workspace OUTPUT_DIR
//
// OUTPUT_DIR/sparse/0/   COLMAP text model: one PINHOLE camera (640x480, 90 degree horizontal field of
//                        view) and 24 images in a lawnmower survey 2 m above the seafloor
// OUTPUT_DIR/seafloor.ply  the seafloor: a 10 x 8 m undulating terrain with two boulders (double PLY)
//
// Images come later from `lutex simulate`; ray casting needs only poses, cameras and the mesh.

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "colmap_integration/sparse_model_io.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geometry/mesh_primitives.h"

namespace {

lutex::Mesh MakeSeafloor() {
  lutex::Mesh seafloor = lutex::MakeHeightFieldMesh(
      [](double x, double y) { return 0.15 * std::sin(0.9 * x) * std::cos(0.7 * y) + 0.05 * std::sin(3.1 * x + 1.3 * y); },
      -5.0, 5.0, -4.0, 4.0, 200, 160);
  seafloor.vertex_texcoords.clear();
  lutex::AppendMesh(lutex::MakeSphereMesh(Eigen::Vector3d(-1.5, 0.8, 0.0), 0.45, 24, 48), &seafloor);
  lutex::AppendMesh(lutex::MakeSphereMesh(Eigen::Vector3d(2.0, -1.2, -0.1), 0.6, 24, 48), &seafloor);
  return seafloor;
}

lutex::SparseModel MakeSurvey() {
  lutex::SparseModel model;
  model.cameras[1] = lutex::Camera::Pinhole(1, 640, 480, 320.0, 320.0);
  std::uint32_t image_id = 1;
  for (int line = 0; line < 3; ++line) {
    for (int step = 0; step < 8; ++step) {
      // Lawnmower: lines along x, alternating direction, 1.5 m apart; camera looks straight down.
      const double x = -3.5 + (line % 2 == 0 ? step : 7 - step) * 1.0;
      const double y = -1.5 + 1.5 * line;
      lutex::Image image;
      image.image_id = image_id;
      image.camera_id = 1;
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%04u.png", image_id);
      image.name = name;
      image.cam_from_world = lutex::CamFromWorldLookingAt(Eigen::Vector3d(x, y, 2.0), Eigen::Vector3d(0, 0, -1),
                                                          Eigen::Vector3d(0, -1, 0));
      model.images[image_id++] = image;
    }
  }
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_example_workspace OUTPUT_DIR\n";
    return 1;
  }
  try {
    const std::filesystem::path output = argv[1];
    std::filesystem::create_directories(output / "images");
    lutex::WriteSparseModel(MakeSurvey(), output / "sparse" / "0", lutex::SparseFormat::kText);
    lutex::WriteMesh(MakeSeafloor(), output / "seafloor.ply");
    std::cout << "example workspace: " << output.string() << " (24 images, mesh seafloor.ply)\n";
  } catch (const std::exception& error) {
    std::cerr << "make_example_workspace: error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
