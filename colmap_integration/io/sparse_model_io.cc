#include "colmap_integration/io/sparse_model_io.h"

#include <stdexcept>

#include "colmap_integration/io/sparse_model_binary.h"
#include "colmap_integration/io/sparse_model_text.h"
#include "lib/util/file_streams.h"

namespace lutex {

namespace fs = std::filesystem;

SparseFormat DetectSparseFormat(const fs::path& folder) {
  if (fs::exists(folder / "cameras.bin")) return SparseFormat::kBinary;
  if (fs::exists(folder / "cameras.txt")) return SparseFormat::kText;
  throw std::runtime_error(folder.string() + ": no COLMAP sparse model here (neither cameras.bin nor cameras.txt)");
}

SparseModel ReadSparseModel(const fs::path& folder) {
  SparseModel model;
  const bool binary = DetectSparseFormat(folder) == SparseFormat::kBinary;
  if (binary) {
    model.cameras = ReadCamerasBinary(folder / "cameras.bin");
    model.images = ReadImagesBinary(folder / "images.bin");
    if (fs::exists(folder / "points3D.bin")) model.points3D = ReadPoints3DBinary(folder / "points3D.bin");
  } else {
    model.cameras = ReadCamerasText(folder / "cameras.txt");
    model.images = ReadImagesText(folder / "images.txt");
    if (fs::exists(folder / "points3D.txt")) model.points3D = ReadPoints3DText(folder / "points3D.txt");
  }
  // Each fault is reported against the file that holds it.
  const char* extension = binary ? ".bin" : ".txt";
  model.CheckCameras((folder / (std::string("cameras") + extension)).string());
  model.CheckImages((folder / (std::string("images") + extension)).string());
  model.CheckPoints3D((folder / (std::string("points3D") + extension)).string());
  return model;
}

void WriteSparseModel(const SparseModel& model, const fs::path& folder, SparseFormat format) {
  model.Check("model to write to " + folder.string());
  fs::create_directories(folder);
  if (format == SparseFormat::kBinary) {
    WriteFileAtomically(folder / "cameras.bin", std::ios::binary,
                        [&](std::ostream& s) { WriteCamerasBinary(model.cameras, s); });
    WriteFileAtomically(folder / "images.bin", std::ios::binary,
                        [&](std::ostream& s) { WriteImagesBinary(model.images, s); });
    WriteFileAtomically(folder / "points3D.bin", std::ios::binary,
                        [&](std::ostream& s) { WritePoints3DBinary(model.points3D, s); });
  } else {
    WriteFileAtomically(folder / "cameras.txt", std::ios::out,
                        [&](std::ostream& s) { WriteCamerasText(model.cameras, s); });
    WriteFileAtomically(folder / "images.txt", std::ios::out,
                        [&](std::ostream& s) { WriteImagesText(model.images, s); });
    WriteFileAtomically(folder / "points3D.txt", std::ios::out,
                        [&](std::ostream& s) { WritePoints3DText(model.points3D, s); });
  }
}

}  // namespace lutex
