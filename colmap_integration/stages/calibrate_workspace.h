#pragma once

// `lutex calibrate`: fits the LUT of a camera-and-lights rig from
//   - targets of known colour (targets file, see lib/calibration/targets.h) seen in the workspace's images
//     or in separate calibration images (their own COLMAP model and mesh of the targets);
//   - a black-and-white chessboard or a ChArUco board with coloured patches in a folder of images of the
//     same camera (no model or mesh needed);
//   - correspondences between the workspace's own survey images (survey_correspondences.h), with or
//     without targets; without, the absolute scale comes from a grey-world albedo the user gives;
//   - optionally pure-water images (beta upper bounds).
//
// Output: the LUT (lut_file.h), `coverage.lut` beside it (alpha = per-node data coverage in [0, 1]),
// `calibration_summary.json` (residuals, iterations, coverage, time), `exposure.json` (the exposure the LUT
// is for and the gains fitted per image, lib/calibration/exposure_record.h; restore reads it),
// `water_prior.json` and `slabs/` pictures.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/output_policy.h"
#include "lib/calibration/albedo_span.h"
#include "lib/calibration/survey_correspondences.h"
#include "lib/calibration/calibrator.h"
#include "lib/calibration/exposure_record.h"
#include "lib/calibration/known_color_sampling.h"
#include "lib/calibration/pure_water_sampling.h"
#include "lib/calibration/solve_plausibility.h"
#include "lib/calibration/water_prior.h"
#include "lib/image/image_io.h"
#include "lib/model/forward_scatter.h"

namespace lutex {

struct CalibrateOptions {
  std::filesystem::path workspace;   // images with their COLMAP model (the survey, or calibration images)
  std::filesystem::path mesh;        // their scene's geometry, in the model's world frame
  std::filesystem::path targets;     // targets file (optional with correspondences)
  // Optional: targets seen in separate calibration images of the same camera, with their own model and
  // mesh; empty: the targets are looked for in `workspace`.
  std::filesystem::path targets_workspace;
  std::filesystem::path targets_mesh;
  // A board of known albedo in the images of `chessboard_images` (a folder; taken with the workspace's
  // camera), found by OpenCV and posed by solvePnP: a black-and-white chessboard
  // (lib/calibration/chessboard_target.h) or a ChArUco board with coloured patches (charuco_target.h),
  // by the file's top-level key "chessboard" or "charuco".
  std::filesystem::path chessboard;
  std::filesystem::path chessboard_images;
  // Correspondence constraints from the workspace's images.
  bool correspondences = false;
  SurveyCorrespondenceOptions correspondence_extraction;
  std::filesystem::path pure_water;  // optional: a workspace of pure-water images of the same camera
  std::filesystem::path output;      // the LUT file; empty: W/lutex/calibration/lut.lut
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // The water the water prior starts from (lib/calibration/water_prior.h: its single-scattering albedo
  // and phase function shape backscatter; the attenuations are fitted), and the most forward scattering
  // that is taken out: "clear", "coastal", or "auto" (ignored in air). Auto fits from the clear water
  // first, measures how much the water scatters (lib/calibration/forward_scatter_estimate.h) and fits
  // again from the preset nearest that, when it is another one or forward scattering is taken out: users
  // rarely know their water, and the presets are starting points, not assumptions. Without known colours
  // the measurement is not trusted to name a water (the fitted attenuations take up the guessed rig's
  // error) and auto keeps the clear one. A rig fitted in the first fit is kept for the second.
  std::string reference_water = "auto";
  // Take forward scattering out of every image before sampling it (lib/model/forward_scatter.h) and record
  // it in the LUT so that restoration takes out the same: the reference water's, lowered per channel to
  // the scattering measured from a first fit (lib/calibration/forward_scatter_estimate.h says why the
  // reference is the most taken out). Ignored in air. Every water scatters; where an image holds less than
  // is taken out (lutex's own simulator renders none unless a scene asks for it), dark surfaces beside
  // bright ones come out too dark, which the measurement keeps small. Costs a second pass of sampling
  // and fitting, and in restoration 2.9 s per 12 MP image (README, 'Forward scattering').
  bool remove_forward_scatter = true;
  // A light-rig file ("lights" as in a scene description, lib/model/light_rig_json.h); when given, its
  // lights replace calibration.grid.shading.rig.
  std::filesystem::path shading_rig;
  // Without a rig file or a light position: fit the rig under the LUT (lib/calibration/water_prior.h: in
  // water lights beside the camera and their beams, in air the flash's position) and shade with it, as if it
  // had been given (recorded in the LUT; the observations are shaded anew). On the Blender boards it brought
  // the worst ColorChecker patch from 19.4 to 5.75 pp (the exact rig: 6.05).
  bool fit_rig = true;
  // Whether to fit one exposure gain per image under the LUT (lib/calibration/exposure_gains.h: strobes
  // that vary, auto exposure), divide the gains out and fit the LUT again:
  //   "auto": when there are correspondences and known colours (on the Blender seafloor with boards the
  //           gains brought the survey from 2.73 to 2.51 pp; from correspondences alone, whose LUT errors
  //           the gains then absorb, they drifted to 0.70 - 1.39 where the truth is 1);
  //   "fit":  whenever there are correspondences;   "none": never.
  // Never from known colours alone: a board image shows the board at one distance, so its gain and the
  // LUT's fall-off with depth could not be told apart. EXIF exposure (lib/image/exposure_settings.h)
  // applies in every case.
  std::string exposure_gains = "auto";
  KnownColorSamplingOptions sampling;
  int pure_water_stride = 8;
  PureWaterScreeningOptions pure_water_screening;
  // Use every pure-water image, also those the screening takes for showing a surface (still warned of).
  bool trust_pure_water = false;
  // The fit itself, as the library takes it: grid.nx/ny/nz, z_near, z_far (the LUT grid; its image size
  // is set from the camera, its levels from nx and ny), grid.shading (how shading treats the lights: the
  // camera centre, a single flash's position or the rig; recorded in the LUT, and the reference LUT is
  // lit the same way), in_air (beta fixed at 0, reference LUT without water), grey_world_albedo (without
  // targets: the mean albedo per channel of the surveyed surfaces, setting the scale), weights.
  CalibrationOptions calibration;
  int num_threads = 0;
  // The stage refuses to start when its memory estimate (stage_memory.h) exceeds this; 0: the machine's
  // available memory.
  std::size_t memory_limit_bytes = 0;

  void Check() const;
};

struct CalibrateSummary {
  std::filesystem::path lut;
  std::size_t num_images = 0;
  std::size_t num_target_images = 0;
  std::size_t num_chessboard_images = 0;  // in which the chessboard was found
  std::size_t num_superpixel_samples = 0;
  std::size_t num_pure_water_images = 0;
  std::size_t num_pure_water_skipped = 0;  // images that seemed to show a surface
  CalibrationSummary calibration;
  // The observations restored with the fitted LUT (lib/calibration/solve_plausibility.h); a solve whose
  // observations restore to implausible albedos is refused before the LUT is written.
  RestoredObservationStats restored_observations;
  // The known colours' albedo range per channel, and a warning per channel they span too narrowly
  // (lib/calibration/albedo_span.h).
  AlbedoSpan albedo_span;
  std::vector<std::string> warnings;
  // The water (or in air the light alone) fitted under the LUT (lib/calibration/water_prior.h); its lut is
  // the calibration's reference and tells the divergence check where the signal can pin an albedo.
  std::optional<WaterPrior> water_prior;
  // The named water the LUT's water prior started from, and why that one: "given", "nearest the
  // measurement" (--reference-water auto) or "not measured without known colours" (auto; the clear water).
  // Empty in air.
  std::string reference_water;
  std::string reference_water_reason;
  // What was taken out of every image as forward scattering (--remove-forward-scatter,
  // lib/calibration/forward_scatter_estimate.h); none otherwise. The LUT records the same.
  ForwardScatter forward_scatter;
  bool forward_scatter_asked = false;  // --remove-forward-scatter in water
  // In water: the water's scattering measured from the first fit, per m (an estimate;
  // forward_scatter_estimate.h says how good). Unset in air.
  std::optional<double> measured_scattering;
  // The exposure the LUT is for: EXIF factors and reference, and the gains fitted per workspace image.
  ExposureRecord exposure;
  std::size_t num_exif_images = 0;  // calibration images whose EXIF gave the factors used
  std::size_t num_observation_images = 0;
};

// What calibrates from besides the workspace and its mesh (targets, boards, pure water, rig), as inputs
// no output may touch (output_policy.h).
void AddCalibrationSources(const CalibrateOptions& options, InputsAndOutputs* paths);

CalibrateSummary CalibrateWorkspace(const CalibrateOptions& options);
// The same on a dive loaded before (`lutex run` loads it once for every stage): `dive` holds the workspace
// and mesh of `options`.
CalibrateSummary CalibrateWorkspace(const CalibrateOptions& options, const LoadedDive& dive);

// The lines the stage prints when done.
void PrintCalibrateSummary(std::ostream& out, const CalibrateSummary& summary);

}  // namespace lutex
