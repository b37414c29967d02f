#pragma once

// COLMAP's text sparse format (cameras.txt, images.txt, points3D.txt). Lines starting with '#' are
// comments. cameras.txt: `CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]`. images.txt: two lines per image,
// `IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME` then `X Y POINT3D_ID ...` (may be empty; -1 = none).
// points3D.txt: `POINT3D_ID X Y Z R G B ERROR (IMAGE_ID POINT2D_IDX)...`. Numbers are written with 17
// significant digits so binary -> text -> binary is lossless.

#include <filesystem>
#include <istream>
#include <map>
#include <ostream>

#include "lib/geometry/sparse_model.h"

namespace lutex {

std::map<std::uint32_t, Camera> ReadCamerasText(std::istream& stream);
std::map<std::uint32_t, Image> ReadImagesText(std::istream& stream);
std::map<std::uint64_t, Point3D> ReadPoints3DText(std::istream& stream);
std::map<std::uint32_t, Camera> ReadCamerasText(const std::filesystem::path& path);
std::map<std::uint32_t, Image> ReadImagesText(const std::filesystem::path& path);
std::map<std::uint64_t, Point3D> ReadPoints3DText(const std::filesystem::path& path);

void WriteCamerasText(const std::map<std::uint32_t, Camera>& cameras, std::ostream& stream);
void WriteImagesText(const std::map<std::uint32_t, Image>& images, std::ostream& stream);
void WritePoints3DText(const std::map<std::uint64_t, Point3D>& points3D, std::ostream& stream);

}  // namespace lutex
