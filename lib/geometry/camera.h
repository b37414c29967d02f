#pragma once

// Cameras with COLMAP's models, parameter orders and conventions (COLMAP 3.8 to 4.x, model ids 0-11).
//
// Pixels: the centre of the top-left pixel is (0.5, 0.5), u right, v down. Camera frame: x right, y down,
// z forward. Projection divides by z, applies the model's distortion to the normalised coordinates and
// then the focal lengths and principal point. The fisheye models (ids 5, 8, 9, 10, 11) first map the
// normalised point (a, b) to the equidistant point theta * (a, b) / r with theta = atan(r), r = |(a, b)|,
// and distort that. Models whose distortion has no closed-form inverse are unprojected by Newton's method
// on the 2-D distortion map (converged to 1e-15 in normalised units).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lutex {

// The largest image side lutex accepts, in pixels: far beyond any camera (a 100 MP sensor is about
// 12 000 a side), so a larger size is a corrupt field, not an image to allocate maps for.
constexpr std::uint64_t kMaxImageSide = 100000;

enum class CameraModelId : int {
  kSimplePinhole = 0,           // f, cx, cy
  kPinhole = 1,                 // fx, fy, cx, cy
  kSimpleRadial = 2,            // f, cx, cy, k
  kRadial = 3,                  // f, cx, cy, k1, k2
  kOpenCV = 4,                  // fx, fy, cx, cy, k1, k2, p1, p2
  kOpenCVFisheye = 5,           // fx, fy, cx, cy, k1, k2, k3, k4
  kFullOpenCV = 6,              // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
  kFOV = 7,                     // fx, fy, cx, cy, omega
  kSimpleRadialFisheye = 8,     // f, cx, cy, k
  kRadialFisheye = 9,           // f, cx, cy, k1, k2
  kThinPrismFisheye = 10,       // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1
  kRadTanThinPrismFisheye = 11  // fx, fy, cx, cy, k0..k5, p0, p1, s0, s1, s2, s3
};

constexpr int kNumCameraModels = 12;

// True for the ids above.
bool IsKnownCameraModelId(int model_id);
// "PINHOLE" etc., as COLMAP spells them.
const std::string& CameraModelName(CameraModelId model_id);
// Throws std::invalid_argument naming `name` when it is not a known model.
CameraModelId CameraModelIdFromName(const std::string& name);
// Throws std::invalid_argument naming the id when it is not a known model.
CameraModelId CameraModelIdFromInt(int model_id);
std::size_t CameraModelNumParams(CameraModelId model_id);
// "fx, fy, cx, cy, k1, k2, p1, p2"
const std::string& CameraModelParamsInfo(CameraModelId model_id);

struct Camera {
  std::uint32_t camera_id = 0;
  CameraModelId model_id = CameraModelId::kPinhole;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  std::vector<double> params;

  // A pinhole camera (model PINHOLE) with the principal point at the image centre.
  static Camera Pinhole(std::uint32_t camera_id, std::uint64_t width, std::uint64_t height, double fx,
                        double fy);

  // Throws std::runtime_error starting with `context` when the parameter count does not match the model,
  // a parameter is not finite, a focal length is not positive or the size is zero or beyond kMaxImageSide.
  void Check(const std::string& context) const;

  // Pixel of a point in the camera frame. The point must have z > 0; otherwise the result is NaN.
  Eigen::Vector2d ImgFromCam(const Eigen::Vector3d& point_in_cam) const;
  // Normalised ray (a, b, 1) through a pixel: every point_in_cam = z * CamFromImg(pixel) projects there.
  Eigen::Vector3d CamFromImg(const Eigen::Vector2d& pixel) const;

  // Focal lengths (fx, fy) and principal point (cx, cy) whatever the model.
  double FocalLengthX() const;
  double FocalLengthY() const;
  double PrincipalPointX() const;
  double PrincipalPointY() const;
};

}  // namespace lutex
