// The water prior recovers a known water, and with a guessed rig a known light geometry, from
// observations made with the simulator's own image formation (I = alpha cos_theta rho + beta from its
// TrueLut): known colours of two albedos, correspondences with a grey-world scale, pure water.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lib/calibration/forward_scatter_estimate.h"
#include "lib/calibration/water_prior.h"
#include "lib/geometry/mesh.h"
#include "lib/model/shading.h"
#include "lib/model/simulator.h"
#include "tests/support/test_scenes.h"

namespace lutex {
namespace {

struct Truth {
  Camera camera = Camera::Pinhole(1, 160, 120, 100, 100);
  FrustumLutGrid grid = testing::LutGrid(16, 12, 8, 0.5, 3.0, 160, 120);
  FrustumLut lut;
  Water water;
};

Water TurbidWater() {
  Water water;
  water.absorption = Eigen::Vector3d(0.5, 0.1, 0.2);
  water.scattering = Eigen::Vector3d(0.35, 0.4, 0.42);
  water.anisotropy_g = 0.9;
  return water;
}

Truth MakeTruth(const LightRig& rig, const Water& water) {
  Truth truth;
  truth.water = water;
  const Mesh nothing;
  const Simulator simulator(nothing, rig, water, SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  truth.lut = simulator.TrueLut(truth.camera, truth.grid);
  return truth;
}

// A regular sample of the frustum: pixels on a 9 x 7 lattice at depths 0.6 to 2.8 m.
template <typename Body>
void ForEachSamplePoint(const Truth& truth, Body body) {
  for (int d = 0; d < 12; ++d) {
    const double z = 0.6 + 0.2 * d;
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 9; ++col) {
        const Eigen::Vector2d pixel(10.0 + 17.5 * col, 8.0 + 17.0 * row);
        body(pixel, (z * truth.camera.CamFromImg(pixel)).eval());
      }
    }
  }
}

std::vector<KnownColorObservation> KnownColours(const Truth& truth) {
  std::vector<KnownColorObservation> observations;
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    for (const Eigen::Vector3d& albedo : {Eigen::Vector3d(0.46, 0.15, 0.013), Eigen::Vector3d(0.08, 0.35, 0.10)}) {
      const LutNode node = truth.lut.Lookup(pixel.x(), pixel.y(), point.z());
      KnownColorObservation o;
      o.pixel = pixel;
      o.point_in_cam = point;
      o.albedo = albedo;
      o.cos_theta = 0.9;
      o.intensity = node.alpha.cwiseProduct(albedo) * o.cos_theta + node.beta;
      observations.push_back(o);
    }
  });
  return observations;
}

// Maximum relative difference of alpha between two LUTs over the sample points.
double MaxRelativeAlphaError(const Truth& truth, const FrustumLut& fitted) {
  double worst = 0.0;
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    const Eigen::Vector3d a = truth.lut.Lookup(pixel.x(), pixel.y(), point.z()).alpha;
    const Eigen::Vector3d b = fitted.Lookup(pixel.x(), pixel.y(), point.z()).alpha;
    worst = std::max(worst, ((b - a).array() / a.array()).abs().maxCoeff());
  });
  return worst;
}

TEST(WaterPrior, RecoversATurbidWaterFromTwoKnownColoursWithTheRigGiven) {
  const LightRig rig = testing::TwoCosineLights(0.4, 1.0, 2.0);
  const Truth truth = MakeTruth(rig, TurbidWater());
  ObservationSet observations;
  observations.known_colors = KnownColours(truth);
  WaterPriorOptions options;
  options.start = *WaterPreset("clear");  // the wrong water to start from: only its b / c ratio is used
  const WaterPrior prior = FitWaterPrior(observations, rig, truth.camera, truth.grid, options);
  std::printf("%s\n", DescribeWaterPrior(prior).c_str());
  // The simulator's signal attenuation is exactly a + b.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(prior.signal_attenuation[c], truth.water.Attenuation()[c], 0.01) << c;
  EXPECT_LT(MaxRelativeAlphaError(truth, prior.lut), 0.02);
  // Backscatter: the shape is fitted with the start water's single-scattering albedo, which differs, so
  // the values (not the attenuation) are what must agree.
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    const Eigen::Vector3d a = truth.lut.Lookup(pixel.x(), pixel.y(), point.z()).beta;
    const Eigen::Vector3d b = prior.lut.Lookup(pixel.x(), pixel.y(), point.z()).beta;
    EXPECT_LT(((b - a).array() / a.array()).abs().maxCoeff(), 0.1) << point.transpose();
  });
  EXPECT_LT(prior.relative_rms.maxCoeff(), 0.02);
  // The fraction of the open water's backscatter reached at each range (what the calibration bounds beta
  // with along pure-water rays): the truth's, beta over the backscatter to the simulator's pure-water range.
  const Simulator open_water(Mesh(), rig, truth.water, SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    const Eigen::Vector3d to_infinity =
        open_water.Backscatter(truth.camera.CamFromImg(pixel).normalized(), SimulatorOptions().max_range);
    const Eigen::Vector3d expected = truth.lut.Lookup(pixel.x(), pixel.y(), point.z()).beta.cwiseQuotient(to_infinity);
    const Eigen::Vector3d reached = prior.backscatter_reached.Lookup(pixel.x(), pixel.y(), point.z()).beta;
    EXPECT_LT((reached - expected).cwiseAbs().maxCoeff(), 0.05) << point.transpose();
  });
}

// The scattering measured from the fitted attenuation (lib/calibration/forward_scatter_estimate.h), in a
// clear, a turbid and a harbour water: never below the water's least b (every water absorbs at least what
// pure water does) and at most the bound its attenuation leaves; exact where the water absorbs no more
// than pure water (the clear one, b 0.04 - 0.05). What is taken out is the smaller of it and the
// reference water's b: the coastal preset's in turbid water, the measurement in the clear one. The preset
// nearest the measurement (--reference-water auto) is the clear one for the clear water and the coastal
// one for the others, whichever preset the fit started from.
TEST(WaterPrior, MeasuresTheScatteringOfClearTurbidAndHarbourWater) {
  Water clear = *WaterPreset("clear");
  clear.scattering = Eigen::Vector3d(0.04, 0.045, 0.05);
  Water harbour;
  harbour.absorption = Eigen::Vector3d(0.6, 0.35, 0.75);
  harbour.scattering = Eigen::Vector3d(0.8, 0.9, 0.85);
  const Eigen::Vector3d pure_water_absorption = WaterPreset("clear")->absorption;
  const Water coastal = *WaterPreset("coastal");
  const LightRig rig = testing::TwoCosineLights(0.4, 1.0, 2.0);
  for (const Water& water : {clear, TurbidWater(), harbour}) {
    const std::string nearest = water.scattering == clear.scattering ? "clear" : "coastal";
    const Truth truth = MakeTruth(rig, water);
    ObservationSet observations;
    observations.known_colors = KnownColours(truth);
    WaterPriorOptions options;
    options.start = coastal;
    const WaterPrior prior = FitWaterPrior(observations, rig, truth.camera, truth.grid, options);
    const double b = MeasuredScattering(prior);
    const ForwardScatter taken_out = ForwardScatterToTakeOut(prior, coastal);
    std::printf("b %.3f %.3f %.3f: measured %.3f, taken out %s\n", water.scattering.x(), water.scattering.y(),
                water.scattering.z(), b, DescribeForwardScatter(taken_out).c_str());
    EXPECT_GE(b, water.scattering.minCoeff() - 0.01);
    EXPECT_LE(b, (water.Attenuation() - pure_water_absorption).minCoeff() + 0.01);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(taken_out.scattering[c], std::min(b, coastal.scattering[c])) << c;
    EXPECT_EQ(taken_out.anisotropy_g, coastal.anisotropy_g);
    EXPECT_EQ(NearestWaterPreset(b), nearest);
    options.start = *WaterPreset("clear");
    const double from_clear = MeasuredScattering(FitWaterPrior(observations, rig, truth.camera, truth.grid, options));
    std::printf("  measured %.3f starting from the clear water\n", from_clear);
    EXPECT_EQ(NearestWaterPreset(from_clear), nearest);
  }
  EXPECT_EQ(NearestWaterPreset(0.0), "clear");
  WaterPrior in_air;
  in_air.in_air = true;
  EXPECT_EQ(MeasuredScattering(in_air), 0.0);
  EXPECT_TRUE(ForwardScatterToTakeOut(in_air, coastal).IsNone());
}

TEST(WaterPrior, FindsThePairOfLightsBesideTheCameraWhenTheRigIsAGuess) {
  const LightRig truth_rig = testing::TwoCosineLights(0.3, 1.0, 0.0);  // isotropic pair at +-0.3 m
  const Truth truth = MakeTruth(truth_rig, *WaterPreset("clear"));
  ObservationSet observations;
  observations.known_colors = KnownColours(truth);
  WaterPriorOptions options;
  options.start = *WaterPreset("clear");
  options.fit_beam = true;
  const WaterPrior prior = FitWaterPrior(observations, PointLightAtCamera(), truth.camera, truth.grid, options);
  std::printf("%s\n", DescribeWaterPrior(prior).c_str());
  ASSERT_EQ(prior.rig.lights.size(), 2u);
  EXPECT_NEAR(std::abs(prior.rig.lights[0].position_in_cam.x()), 0.3, 1e-9);
  EXPECT_NEAR(prior.rig.lights[0].position_in_cam.y(), 0.0, 1e-9);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(prior.signal_attenuation[c], truth.water.Attenuation()[c], 0.01) << c;
  EXPECT_LT(MaxRelativeAlphaError(truth, prior.lut), 0.02);

  // The camera-centred guess itself, kept, fits worse.
  options.fit_beam = false;
  const WaterPrior kept = FitWaterPrior(observations, PointLightAtCamera(), truth.camera, truth.grid, options);
  EXPECT_GT(kept.relative_rms.maxCoeff(), 3.0 * prior.relative_rms.maxCoeff() + 1e-4);
}

TEST(WaterPrior, CorrespondencesWithAGreyWorldAndPureWaterFixTheWaterWithoutKnownColours) {
  const LightRig rig = testing::TwoCosineLights(0.4, 1.0, 2.0);
  const Truth truth = MakeTruth(rig, TurbidWater());
  const Eigen::Vector3d albedo(0.3, 0.3, 0.3);
  ObservationSet observations;
  // One surface point seen from two ranges: the second view 0.7 m farther, elsewhere in the image.
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    if (point.z() > 2.0) return;
    CorrespondenceObservation o;
    const Eigen::Vector2d other(160.0 - pixel.x(), pixel.y());
    const Eigen::Vector3d far_point = (point.z() + 0.7) * truth.camera.CamFromImg(other);
    for (auto [view, p, x] : {std::tuple{&o.first, pixel, point}, std::tuple{&o.second, other, far_point}}) {
      const LutNode node = truth.lut.Lookup(p.x(), p.y(), x.z());
      view->pixel = p;
      view->point_in_cam = x;
      view->cos_theta = 0.9;
      view->intensity = node.alpha.cwiseProduct(albedo) * 0.9 + node.beta;
    }
    observations.correspondences.push_back(o);
  });
  const Mesh nothing;
  const Simulator pure_water(nothing, rig, truth.water, SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()));
  for (int row = 5; row < 120; row += 20) {
    for (int col = 5; col < 160; col += 20) {
      PureWaterObservation o;
      o.pixel = Eigen::Vector2d(col, row);
      o.intensity = pure_water.Backscatter(truth.camera.CamFromImg(o.pixel).normalized(), SimulatorOptions().max_range);
      observations.pure_water.push_back(o);
    }
  }
  WaterPriorOptions options;
  options.start = *WaterPreset("coastal");
  options.grey_world_albedo = albedo;
  const WaterPrior prior = FitWaterPrior(observations, rig, truth.camera, truth.grid, options);
  std::printf("%s\n", DescribeWaterPrior(prior).c_str());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(prior.signal_attenuation[c], truth.water.Attenuation()[c], 0.02) << c;
  EXPECT_LT(MaxRelativeAlphaError(truth, prior.lut), 0.05);
}

// In air, a flash beside the lens (above-left as in the unseen data, right as in the Blender
// set, far below) and a white board tilted every way: the observations come shaded from the camera centre,
// as calibration first shades them, and the fit finds the flash from how its light falls off and how it
// shades the tilted board.
class FlashInAir : public ::testing::TestWithParam<Eigen::Vector3d> {};

TEST_P(FlashInAir, TheFitFindsWhereTheFlashIs) {
  LightRig flash = PointLightAtCamera();
  flash.lights[0].position_in_cam = GetParam();
  flash.lights[0].profile = BeamProfile::kCosinePower;
  flash.lights[0].exponent = 1.3;  // between the beams the fit tries
  const Truth truth = MakeTruth(flash, Water::Air());
  Shading exact, camera_centred;
  exact.rig = flash;
  ObservationSet observations;
  ForEachSamplePoint(truth, [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point) {
    for (const Eigen::Vector3d& tilt : {Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d(0.5, 0.0, -1.0),
                                        Eigen::Vector3d(-0.4, 0.3, -1.0), Eigen::Vector3d(0.2, -0.5, -1.0)}) {
      KnownColorObservation o;
      o.pixel = pixel;
      o.point_in_cam = point;
      o.albedo = Eigen::Vector3d(0.8, 0.8, 0.8);
      o.normal_in_cam = tilt.normalized();
      o.cos_theta = camera_centred.Cosine(point, o.normal_in_cam);
      const double cos_theta = exact.Cosine(point, o.normal_in_cam);
      o.intensity = truth.lut.Lookup(pixel.x(), pixel.y(), point.z()).alpha.cwiseProduct(o.albedo) * cos_theta;
      if (o.cos_theta > 0.1 && cos_theta > 0.1) observations.known_colors.push_back(o);
    }
  });
  WaterPriorOptions options;
  options.start = Water::Air();
  options.fit_beam = true;
  const WaterPrior prior = FitWaterPrior(observations, PointLightAtCamera(), truth.camera, truth.grid, options);
  std::printf("%s\n", DescribeWaterPrior(prior).c_str());
  EXPECT_TRUE(prior.in_air);
  ASSERT_EQ(prior.rig.lights.size(), 1u);
  // Two search steps: a light direction off by under 3 degrees at the nearest sample, 0.6 m away.
  EXPECT_LT((prior.rig.lights[0].position_in_cam - GetParam()).norm(), 0.021);
  EXPECT_EQ(prior.backscatter_scale, Eigen::Vector3d::Zero());
  EXPECT_LT(MaxRelativeAlphaError(truth, prior.lut), 0.06);

  // The camera-centred guess itself, kept, fits worse.
  options.fit_beam = false;
  const WaterPrior kept = FitWaterPrior(observations, PointLightAtCamera(), truth.camera, truth.grid, options);
  EXPECT_GT(kept.relative_rms.maxCoeff(), 3.0 * prior.relative_rms.maxCoeff() + 1e-4);
}

INSTANTIATE_TEST_SUITE_P(WaterPrior, FlashInAir,
                         ::testing::Values(Eigen::Vector3d(-0.10, -0.10, 0.0), Eigen::Vector3d(0.10, 0.0, 0.0),
                                           Eigen::Vector3d(0.03, 0.22, 0.0)));

TEST(WaterPrior, RefusesWhatCannotFixIt) {
  const Truth truth = MakeTruth(PointLightAtCamera(), *WaterPreset("clear"));
  WaterPriorOptions options;
  options.start = *WaterPreset("clear");
  EXPECT_THROW(FitWaterPrior(ObservationSet(), PointLightAtCamera(), truth.camera, truth.grid, options),
               std::invalid_argument);
  ObservationSet only_correspondences;
  only_correspondences.correspondences.resize(3);
  EXPECT_THROW(FitWaterPrior(only_correspondences, PointLightAtCamera(), truth.camera, truth.grid, options),
               std::invalid_argument);
}

}  // namespace
}  // namespace lutex
