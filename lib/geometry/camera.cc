#include "lib/geometry/camera.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

namespace lutex {
namespace {

struct ModelInfo {
  CameraModelId id;
  std::string name;
  std::size_t num_params;
  std::string params_info;
  bool single_focal;  // params start with f, cx, cy instead of fx, fy, cx, cy
  bool fisheye;       // distortion acts on the equidistant point theta * (a, b) / r
};

const std::array<ModelInfo, kNumCameraModels>& Models() {
  static const std::array<ModelInfo, kNumCameraModels> models = {{
      {CameraModelId::kSimplePinhole, "SIMPLE_PINHOLE", 3, "f, cx, cy", true, false},
      {CameraModelId::kPinhole, "PINHOLE", 4, "fx, fy, cx, cy", false, false},
      {CameraModelId::kSimpleRadial, "SIMPLE_RADIAL", 4, "f, cx, cy, k", true, false},
      {CameraModelId::kRadial, "RADIAL", 5, "f, cx, cy, k1, k2", true, false},
      {CameraModelId::kOpenCV, "OPENCV", 8, "fx, fy, cx, cy, k1, k2, p1, p2", false, false},
      {CameraModelId::kOpenCVFisheye, "OPENCV_FISHEYE", 8, "fx, fy, cx, cy, k1, k2, k3, k4", false, true},
      {CameraModelId::kFullOpenCV, "FULL_OPENCV", 12,
       "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6", false, false},
      {CameraModelId::kFOV, "FOV", 5, "fx, fy, cx, cy, omega", false, false},
      {CameraModelId::kSimpleRadialFisheye, "SIMPLE_RADIAL_FISHEYE", 4, "f, cx, cy, k", true, true},
      {CameraModelId::kRadialFisheye, "RADIAL_FISHEYE", 5, "f, cx, cy, k1, k2", true, true},
      {CameraModelId::kThinPrismFisheye, "THIN_PRISM_FISHEYE", 12,
       "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1", false, true},
      {CameraModelId::kRadTanThinPrismFisheye, "RAD_TAN_THIN_PRISM_FISHEYE", 16,
       "fx, fy, cx, cy, k0, k1, k2, k3, k4, k5, p0, p1, s0, s1, s2, s3", false, true},
  }};
  return models;
}

const ModelInfo& Info(CameraModelId id) { return Models()[static_cast<std::size_t>(id)]; }

// FOV model (Devernay and Faugeras), with COLMAP's series expansions near omega = 0 and r = 0.
Eigen::Vector2d DistortFov(double omega, const Eigen::Vector2d& p) {
  constexpr double kEpsilon = 1e-4;
  const double radius2 = p.squaredNorm();
  const double omega2 = omega * omega;
  double factor;
  if (omega2 < kEpsilon) {
    factor = omega2 * radius2 / 3.0 - omega2 / 12.0 + 1.0;
  } else if (radius2 < kEpsilon) {
    const double tan_half_omega = std::tan(omega / 2.0);
    factor = -2.0 * tan_half_omega * (4.0 * radius2 * tan_half_omega * tan_half_omega - 3.0) / (3.0 * omega);
  } else {
    const double radius = std::sqrt(radius2);
    factor = std::atan(radius * 2.0 * std::tan(omega / 2.0)) / (radius * omega);
  }
  return factor * p;
}

// Tangential (decentering) terms of the Brown-Conrady model as COLMAP writes them.
Eigen::Vector2d Tangential(double p1, double p2, const Eigen::Vector2d& p) {
  const double u = p.x(), v = p.y();
  const double r2 = p.squaredNorm();
  return {2.0 * p1 * u * v + p2 * (r2 + 2.0 * u * u), 2.0 * p2 * u * v + p1 * (r2 + 2.0 * v * v)};
}

// The model's distortion map on the normalised (or, for fisheye models, equidistant) point.
Eigen::Vector2d Distort(CameraModelId id, const double* k, const Eigen::Vector2d& p) {
  const double r2 = p.squaredNorm();
  switch (id) {
    case CameraModelId::kSimplePinhole:
    case CameraModelId::kPinhole:
      return p;
    case CameraModelId::kSimpleRadial:
      return p * (1.0 + k[0] * r2);
    case CameraModelId::kRadial:
      return p * (1.0 + k[0] * r2 + k[1] * r2 * r2);
    case CameraModelId::kOpenCV:
      return p * (1.0 + k[0] * r2 + k[1] * r2 * r2) + Tangential(k[2], k[3], p);
    case CameraModelId::kFullOpenCV: {
      const double r4 = r2 * r2, r6 = r4 * r2;
      const double radial =
          (1.0 + k[0] * r2 + k[1] * r4 + k[4] * r6) / (1.0 + k[5] * r2 + k[6] * r4 + k[7] * r6);
      return p * radial + Tangential(k[2], k[3], p);
    }
    case CameraModelId::kFOV:
      return DistortFov(k[0], p);
    case CameraModelId::kOpenCVFisheye: {
      const double t2 = r2, t4 = t2 * t2;
      return p * (1.0 + k[0] * t2 + k[1] * t4 + k[2] * t4 * t2 + k[3] * t4 * t4);
    }
    case CameraModelId::kSimpleRadialFisheye:
      return p * (1.0 + k[0] * r2);
    case CameraModelId::kRadialFisheye:
      return p * (1.0 + k[0] * r2 + k[1] * r2 * r2);
    case CameraModelId::kThinPrismFisheye: {
      const double r4 = r2 * r2;
      const double radial = k[0] * r2 + k[1] * r4 + k[4] * r4 * r2 + k[5] * r4 * r4;
      return p * (1.0 + radial) + Tangential(k[2], k[3], p) + Eigen::Vector2d(k[6], k[7]) * r2;
    }
    case CameraModelId::kRadTanThinPrismFisheye: {
      // k0..k5 radial in theta^2, then tangential (p0, p1) and thin prism (s0..s3) on the result.
      double th_radial = 1.0, power = 1.0;
      for (int i = 0; i < 6; ++i) {
        power *= r2;
        th_radial += k[i] * power;
      }
      const Eigen::Vector2d q = th_radial * p;
      const double q2 = q.squaredNorm(), q4 = q2 * q2;
      const double p0 = k[6], p1 = k[7];
      const Eigen::Vector2d tangential(2.0 * p1 * q.x() * q.y() + p0 * (q2 + 2.0 * q.x() * q.x()),
                                       2.0 * p0 * q.x() * q.y() + p1 * (q2 + 2.0 * q.y() * q.y()));
      return q + tangential + Eigen::Vector2d(k[8] * q2 + k[9] * q4, k[10] * q2 + k[11] * q4);
    }
  }
  return p;
}

// Solves Distort(p) = target for p by Newton's method with a central-difference Jacobian.
Eigen::Vector2d Undistort(CameraModelId id, const double* k, const Eigen::Vector2d& target) {
  Eigen::Vector2d p = target;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::Vector2d residual = Distort(id, k, p) - target;
    const double step = 1e-7 * std::max(1.0, p.norm());
    Eigen::Matrix2d jacobian;
    for (int c = 0; c < 2; ++c) {
      Eigen::Vector2d delta = Eigen::Vector2d::Zero();
      delta[c] = step;
      jacobian.col(c) = (Distort(id, k, p + delta) - Distort(id, k, p - delta)) / (2.0 * step);
    }
    const Eigen::Vector2d update = jacobian.partialPivLu().solve(residual);
    if (!update.allFinite()) break;
    p -= update;
    if (update.norm() <= 1e-15 * std::max(1.0, p.norm())) break;
  }
  return p;
}

}  // namespace

bool IsKnownCameraModelId(int model_id) { return model_id >= 0 && model_id < kNumCameraModels; }

const std::string& CameraModelName(CameraModelId model_id) { return Info(model_id).name; }

CameraModelId CameraModelIdFromName(const std::string& name) {
  for (const ModelInfo& info : Models()) {
    if (info.name == name) return info.id;
  }
  throw std::invalid_argument("unknown camera model '" + name + "'");
}

CameraModelId CameraModelIdFromInt(int model_id) {
  if (!IsKnownCameraModelId(model_id)) {
    throw std::invalid_argument("unknown camera model id " + std::to_string(model_id) +
                                " (lutex knows ids 0-" + std::to_string(kNumCameraModels - 1) + ")");
  }
  return static_cast<CameraModelId>(model_id);
}

std::size_t CameraModelNumParams(CameraModelId model_id) { return Info(model_id).num_params; }

const std::string& CameraModelParamsInfo(CameraModelId model_id) { return Info(model_id).params_info; }

Camera Camera::Pinhole(std::uint32_t camera_id, std::uint64_t width, std::uint64_t height, double fx,
                       double fy) {
  Camera camera;
  camera.camera_id = camera_id;
  camera.model_id = CameraModelId::kPinhole;
  camera.width = width;
  camera.height = height;
  camera.params = {fx, fy, static_cast<double>(width) / 2.0, static_cast<double>(height) / 2.0};
  return camera;
}

void Camera::Check(const std::string& context) const {
  const ModelInfo& info = Info(model_id);
  std::ostringstream problem;
  if (params.size() != info.num_params) {
    problem << "camera " << camera_id << " has model " << info.name << ", which takes " << info.num_params
            << " parameters (" << info.params_info << "), but " << params.size() << " are given";
  } else if (width == 0 || height == 0) {
    problem << "camera " << camera_id << " has an empty image size " << width << "x" << height;
  } else if (width > kMaxImageSide || height > kMaxImageSide) {
    problem << "camera " << camera_id << " has an image size " << width << "x" << height << ", beyond "
            << kMaxImageSide << " pixels a side (a corrupt size field?)";
  } else {
    for (double value : params) {
      if (!std::isfinite(value)) {
        problem << "camera " << camera_id << " has a parameter that is not finite";
        break;
      }
    }
    if (problem.str().empty() && (FocalLengthX() <= 0.0 || FocalLengthY() <= 0.0)) {
      problem << "camera " << camera_id << " has a focal length that is not positive";
    }
  }
  if (!problem.str().empty()) throw std::runtime_error(context + ": " + problem.str());
}

double Camera::FocalLengthX() const { return params[0]; }
double Camera::FocalLengthY() const { return Info(model_id).single_focal ? params[0] : params[1]; }
double Camera::PrincipalPointX() const { return Info(model_id).single_focal ? params[1] : params[2]; }
double Camera::PrincipalPointY() const { return Info(model_id).single_focal ? params[2] : params[3]; }

Eigen::Vector2d Camera::ImgFromCam(const Eigen::Vector3d& point_in_cam) const {
  if (!(point_in_cam.z() > std::numeric_limits<double>::epsilon())) {
    return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  const ModelInfo& info = Info(model_id);
  Eigen::Vector2d p = point_in_cam.head<2>() / point_in_cam.z();
  if (info.fisheye) {
    const double r = p.norm();
    if (r > std::numeric_limits<double>::epsilon()) p *= std::atan(r) / r;
  }
  const Eigen::Vector2d distorted = Distort(model_id, params.data() + (info.single_focal ? 3 : 4), p);
  return {FocalLengthX() * distorted.x() + PrincipalPointX(),
          FocalLengthY() * distorted.y() + PrincipalPointY()};
}

Eigen::Vector3d Camera::CamFromImg(const Eigen::Vector2d& pixel) const {
  const ModelInfo& info = Info(model_id);
  const Eigen::Vector2d distorted((pixel.x() - PrincipalPointX()) / FocalLengthX(),
                                  (pixel.y() - PrincipalPointY()) / FocalLengthY());
  Eigen::Vector2d p = distorted;
  if (model_id != CameraModelId::kPinhole && model_id != CameraModelId::kSimplePinhole) {
    p = Undistort(model_id, params.data() + (info.single_focal ? 3 : 4), distorted);
  }
  if (info.fisheye) {
    const double theta = p.norm();
    if (theta >= M_PI / 2.0) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    if (theta > std::numeric_limits<double>::epsilon()) p *= std::tan(theta) / theta;
  }
  return {p.x(), p.y(), 1.0};
}

}  // namespace lutex
