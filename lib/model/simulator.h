#pragma once

// A physically based forward renderer of a camera with co-moving lights in water, independent of the
// LUT (it is what the LUT is tested against). For each pixel, with x the surface point in the camera
// frame and d_cam = |x|:
//
//   direct      = rho / pi * sum_l I_l f_l(psi_l) cos(i_l) / d_l^2 * exp(-c (d_l + d_cam)) * visible_l
//   backscatter = integral_s1^D  b * p_HG(cos angle_l(s)) * I_l f_l(psi_l(s)) / d_l(s)^2
//                               * exp(-c (d_l(s) + s)) ds,  summed over lights
//
// per channel (the backscatter of a pixel is read from a BackscatterTable made once per camera), with
// d_l the distance from light l, i_l its incidence angle at the surface (shading
// normal), psi_l the angle from its beam axis, visible_l a shadow ray, c = a + b, D the range to the
// surface (or `max_range` where the ray meets nothing: pure water), s1 the distance where the water
// starts (`water_start`, the camera port). Backscatter is single scattering
// (as in the shared Blender renders) without shadowing inside the volume, integrated by the midpoint
// rule in w = log(1 + (s - s1) / s1), which puts steps where the integrand changes fast (near the camera)
// and converges to < 0.5 % with the default 96 steps (tested against 4096 and a brute-force integral).
//
// TrueLut evaluates, at every LUT node, what a perfect calibration should find from the same physics:
//   alpha(x) = sum_l I_l f_l(psi_l) / d_l^2 * exp(-c (d_l + |x|)) / pi,   beta(x) = backscatter to |x|,
// which is exact for I = alpha cos_theta rho + beta when cos_theta is the rig's shading (Shading with this
// rig, lib/model/shading.h; the water loss on the light paths then differs slightly between lights); with
// shading from one position (the camera centre) it is exact only where cos(i_l) = cos_theta, and the
// difference is the model error, not a simulator error.

#include <cstdint>
#include <memory>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/geometry/camera.h"
#include "lib/geometry/mesh.h"
#include "lib/geometry/rigid3d.h"
#include "lib/lut/frustum_lut.h"
#include "lib/model/backscatter_table.h"
#include "lib/model/light_rig.h"
#include "lib/model/surface_albedo.h"
#include "lib/model/water.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/raycast_scene.h"

namespace lutex {

struct SimulatorOptions {
  // Steps of the backscatter integral along each ray.
  int backscatter_steps = 96;
  // Distance s1 [m] from the centre of projection where the water starts (the camera's port). Besides
  // being physical it keeps backscatter finite for a light at the camera centre, whose integrand grows as
  // 1 / s^2 towards the camera. It is also the scale of the log substitution, so every step is the same
  // fraction of its distance from the port.
  double water_start = 0.02;
  // Range of rays that hit nothing (pure water), metres.
  double max_range = 30.0;
  // Cast shadow rays to the lights.
  bool shadows = true;
  // Spread the light from the surface by the water's forward scattering on its way to the camera
  // (lib/model/forward_scatter.h, with the water's b and g): the direct term is rendered, then
  // AddForwardScatter redistributes it over the ray-cast ranges; backscatter is added after. The same
  // operator that `--remove-forward-scatter` inverts, so TrueLut stays exact for an image it corrected.
  // Off: the surface is seen sharp at any range (the renders milestone 1's tests were made with).
  bool forward_scatter = false;
  // Threads over image rows; <= 0 means all cores.
  int num_threads = 0;

  // Throws std::invalid_argument on nonsense.
  void Check() const;
};

class Simulator {
 public:
  // Keeps a reference to the mesh (which may be large): it must outlive the simulator. A mesh without
  // faces renders pure water (backscatter to max_range everywhere).
  Simulator(const Mesh& mesh, const LightRig& rig, const Water& water, const SurfaceAlbedo& albedo,
            const SimulatorOptions& options = {});

  // The ray caster's maps of the simulated mesh (ground-truth depth and normals), or "nothing hit"
  // everywhere for a mesh without faces.
  GeometryMaps RenderGeometry(const CameraRays& rays, const Rigid3d& cam_from_world,
                              const GeometryMapsOptions& options) const;

  // The backscatter of every pixel of `rays.camera()` at every range, computed once per camera.
  BackscatterTable MakeBackscatterTable(const CameraRays& rays) const;

  // Noise-free linear radiance (CV_32FC3, RGB) seen by the camera at cam_from_world.
  cv::Mat Render(const CameraRays& rays, const BackscatterTable& backscatter, const Rigid3d& cam_from_world) const;
  // The same, making the backscatter table first (for one-off renders).
  cv::Mat Render(const CameraRays& rays, const Rigid3d& cam_from_world) const;

  // The true albedo seen through each pixel centre (no light, no water): CV_32FC3 RGB, NaN where the ray
  // meets nothing.
  cv::Mat RenderAlbedo(const CameraRays& rays, const Rigid3d& cam_from_world) const;

  // The backscatter integrand at distance s along the unit ray `direction_in_cam`.
  Eigen::Array3d BackscatterDensity(const Eigen::Vector3d& direction_in_cam, double s) const;
  // Backscatter along the unit ray `direction_in_cam` from the camera to `range` (direct integration).
  Eigen::Vector3d Backscatter(const Eigen::Vector3d& direction_in_cam, double range) const;
  // alpha at a point in the camera frame (the TrueLut formula above).
  Eigen::Vector3d SignalFactor(const Eigen::Vector3d& point_in_cam) const;
  // The LUT a perfect calibration should find for this rig and water on `grid`.
  FrustumLut TrueLut(const Camera& camera, const FrustumLutGrid& grid) const;

 private:
  // Irradiance-like term of light l at a point: I f / d^2 exp(-c d) (no cosine).
  Eigen::Vector3d LightTerm(const Light& light, const Eigen::Vector3d& point_in_cam, Eigen::Vector3d* to_light) const;

  const Mesh& mesh_;
  LightRig rig_;
  Water water_;
  SurfaceAlbedo albedo_;
  SimulatorOptions options_;
  std::unique_ptr<RaycastScene> scene_;  // null for a mesh without faces
};

}  // namespace lutex
