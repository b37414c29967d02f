#pragma once

// COLMAP's binary sparse format (cameras.bin, images.bin, points3D.bin), little-endian:
//   cameras.bin:  uint64 count; per camera: uint32 id, int32 model id, uint64 width, uint64 height,
//                 float64 params[model's count]
//   images.bin:   uint64 count; per image: uint32 id, float64 qw qx qy qz tx ty tz (cam_from_world),
//                 uint32 camera id, name as bytes up to a NUL, uint64 n, n x (float64 x, float64 y,
//                 uint64 point3D id; 2^64-1 = none)
//   points3D.bin: uint64 count; per point: uint64 id, float64 x y z, uint8 r g b, float64 error,
//                 uint64 track length, length x (uint32 image id, uint32 point2D index)
// The stream overloads parse and throw without a file name; the path overloads name the file.

#include <filesystem>
#include <istream>
#include <map>
#include <ostream>

#include "lib/geometry/sparse_model.h"

namespace lutex {

std::map<std::uint32_t, Camera> ReadCamerasBinary(std::istream& stream);
std::map<std::uint32_t, Image> ReadImagesBinary(std::istream& stream);
std::map<std::uint64_t, Point3D> ReadPoints3DBinary(std::istream& stream);
std::map<std::uint32_t, Camera> ReadCamerasBinary(const std::filesystem::path& path);
std::map<std::uint32_t, Image> ReadImagesBinary(const std::filesystem::path& path);
std::map<std::uint64_t, Point3D> ReadPoints3DBinary(const std::filesystem::path& path);

void WriteCamerasBinary(const std::map<std::uint32_t, Camera>& cameras, std::ostream& stream);
void WriteImagesBinary(const std::map<std::uint32_t, Image>& images, std::ostream& stream);
void WritePoints3DBinary(const std::map<std::uint64_t, Point3D>& points3D, std::ostream& stream);

}  // namespace lutex
