#pragma once

// How much forward scattering to take out of the images (lib/model/forward_scatter.h): the reference
// water's, lowered to what the calibration's own observations say the water scatters.
//
// Taking out more than the water scatters darkens what lies beside bright surfaces, and far more than
// taking out too little brightens it: lutex's simulated clear water (b 0.04 - 0.05 per m), rendered with
// its forward scattering, restored to 1.82 pp uncorrected, 5.36 pp corrected with the coastal preset's b
// (0.35 - 0.40) and 1.59 pp with the b measured here; in its harbour water (b 0.8 - 0.9) the coastal
// preset's b gave 19.8 / 19.6 pp (two rigs), none 22.1 / 20.3, and the measured b (1.35 / 1.01, near or
// above the truth) 23.2 / 25.7: there the removal amplifies more error than it takes out (README,
// 'Forward scattering'). So the reference water's b is the most that is taken out, and the measurement
// only lowers it: a user who names a turbid water in clear water no longer loses the dark surfaces.
//
// The measurement. The water prior (water_prior.h) fits each channel's signal attenuation cs. With
// forward scattering in the images the signal attenuates a little less than with the water's whole
// attenuation a + b, and the fitted cs hardly depends on how much of it was taken out (Blender turbid
// boards: green cs 0.452 / 0.468 / 0.484 per m with half, all and 1.5 times the water's b taken out).
// A water absorbs at least what pure water does, a_c >= a_w,c, and its particles scatter nearly alike at
// every wavelength (b is grey), so each channel bounds b from above and the least of them is taken:
//   b = min over c of (cs_c - a_w,c),   at least 0,
// with a_w the clear preset's absorption (clear oceanic water, 0.35 / 0.05 / 0.02 per m in r g b). It is
// too high by the water's absorption beyond pure water's in the channel where that is least (dissolved
// matter and particles absorb as well): on the simulator's own alpha (water_prior_test.cc) 0.45 for a
// turbid water of b 0.35 - 0.42, 1.05 for the harbour water; on the Blender turbid boards 0.39.
// It is an estimate rather than a bound, since cs is fitted: in lutex's simulated clear water (b 0.04)
// it came out at 0.018 and 0 (two rigs), on the Blender turbid boards with the exact rig at 0.32.
// Where the prior's model of the rig is off (a guessed rig in harbour water), cs and so b come out higher
// still, which the reference water's bound catches.
//
// The anisotropy g is not measured: it is the reference water's (0.9; natural waters have 0.85 - 0.95).

#include <string>

#include "lib/calibration/water_prior.h"
#include "lib/model/forward_scatter.h"
#include "lib/model/water.h"

namespace lutex {

// b per metre from `prior` as above (0 in air).
double MeasuredScattering(const WaterPrior& prior);

// The named water (lib/model/water.h) whose scattering, averaged over the channels, is nearest `measured`
// on a log scale: what `lutex calibrate --reference-water auto` starts the final fit from. The presets' b
// differ eightfold (0.045 and 0.38 per m), so the boundary lies at 0.13 per m, far from both: the Blender
// clear boards measure 0.078, the turbid ones 0.39; lutex's simulated clear, coastal and harbour waters
// 0.018, 0.45 and 1.05.
std::string NearestWaterPreset(double measured);

// Per channel the smaller of `reference`'s b and the measured b, with `reference`'s g. None in air, or
// where either is 0.
ForwardScatter ForwardScatterToTakeOut(const WaterPrior& prior, const Water& reference);

}  // namespace lutex
