#include "tests/support/test_cameras.h"

namespace lutex::testing {

Camera MakeCamera(CameraModelId model_id, std::uint32_t camera_id) {
  Camera camera;
  camera.camera_id = camera_id;
  camera.model_id = model_id;
  camera.width = 640;
  camera.height = 480;
  switch (model_id) {
    case CameraModelId::kSimplePinhole: camera.params = {500, 320, 240}; break;
    case CameraModelId::kPinhole: camera.params = {500, 520, 322, 238}; break;
    case CameraModelId::kSimpleRadial: camera.params = {500, 320, 240, -0.08}; break;
    case CameraModelId::kRadial: camera.params = {500, 320, 240, -0.08, 0.01}; break;
    case CameraModelId::kOpenCV: camera.params = {500, 520, 322, 238, -0.1, 0.02, 0.001, -0.0015}; break;
    case CameraModelId::kOpenCVFisheye: camera.params = {300, 310, 322, 238, 0.05, -0.01, 0.002, -0.0004}; break;
    case CameraModelId::kFullOpenCV:
      camera.params = {500, 520, 322, 238, -0.1, 0.02, 0.001, -0.0015, 0.001, 0.01, 0.002, 0.0005};
      break;
    case CameraModelId::kFOV: camera.params = {400, 410, 322, 238, 0.9}; break;
    case CameraModelId::kSimpleRadialFisheye: camera.params = {300, 320, 240, 0.04}; break;
    case CameraModelId::kRadialFisheye: camera.params = {300, 320, 240, 0.04, -0.005}; break;
    case CameraModelId::kThinPrismFisheye:
      camera.params = {300, 310, 322, 238, 0.05, -0.01, 0.001, -0.001, 0.002, -0.0004, 0.001, -0.0008};
      break;
    case CameraModelId::kRadTanThinPrismFisheye:
      camera.params = {300, 310, 322, 238, 0.05, -0.01, 0.002, -0.0004, 0.0001, -0.00002,
                       0.001, -0.001, 0.0008, 0.0001, -0.0006, 0.00005};
      break;
  }
  return camera;
}

}  // namespace lutex::testing
