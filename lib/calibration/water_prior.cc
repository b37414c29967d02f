#include "lib/calibration/water_prior.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "lib/geometry/mesh.h"
#include "lib/model/shading.h"
#include "lib/model/simulator.h"
#include "lib/model/surface_albedo.h"
#include "lib/util/median.h"
#include "lib/util/parallel_for.h"

namespace lutex {
namespace {

// At most this many observations of each kind enter the fit (an even subsample): four numbers per
// channel are fixed long before, and the search evaluates every candidate pair on all of them.
constexpr std::size_t kMaxFitObservations = 8000;
// The global search: attenuations 0 to 1 per metre by 0.04, then by 8 % steps to 3 per metre.
std::vector<double> GlobalAttenuations() {
  std::vector<double> values;
  for (int k = 0; k <= 25; ++k) values.push_back(0.04 * k);
  while (values.back() < 3.0) values.push_back(values.back() * 1.08);
  return values;
}
// The local search: 21 steps across the global grid's spacing on either side of its best value.
constexpr int kLocalSteps = 10;
// Beam profiles tried when the rig's beams are a guess (cosine-power exponents; 0 = isotropic).
constexpr double kBeamExponents[] = {0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0};
// In air, where a guessed rig's single light (a flash) may be: a square of this half-size across the
// camera's x and y, searched by kFlashCoarseStep, then by kFlashFineStep around the best of that.
constexpr double kFlashSearchHalfSize = 0.3;  // metres
constexpr double kFlashCoarseStep = 0.05;
constexpr double kFlashFineStep = 0.01;

// The fitted observations, per kind, as the fit needs them (one channel at a time).
struct FitData {
  std::vector<const KnownColorObservation*> known;
  std::vector<const CorrespondenceObservation*> correspondences;
  std::vector<const PureWaterObservation*> pure_water;
  Eigen::Vector3d floor = Eigen::Vector3d::Zero();  // noise floor per channel, in intensity
};

template <typename T>
std::vector<const T*> Subsample(const std::vector<T>& all) {
  std::vector<const T*> chosen;
  const std::size_t stride = std::max<std::size_t>(1, (all.size() + kMaxFitObservations - 1) / kMaxFitObservations);
  for (std::size_t i = 0; i < all.size(); i += stride) chosen.push_back(&all[i]);
  return chosen;
}

// The floor of the relative residuals: the channel's median observed intensity. A pixel brighter than
// that counts by its relative error, a darker one by its error in units of the median: the black squares
// of a chessboard (albedo 0.04, next to white ones, at the noise) then no longer steer the fit. With 2 %
// of the median they did: a simulated chessboard fitted the red attenuation at 3.4 per m instead of 0.39
// and the restored survey went from 4.6 to 13.7 pp. (The Blender boards fit the same at 30 % or 100 %.)
Eigen::Vector3d NoiseFloor(const FitData& data) {
  Eigen::Vector3d floor;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> values;
    for (const KnownColorObservation* o : data.known) values.push_back(o->intensity[c]);
    for (const CorrespondenceObservation* o : data.correspondences) {
      values.push_back(o->first.intensity[c]);
      values.push_back(o->second.intensity[c]);
    }
    for (const PureWaterObservation* o : data.pure_water) values.push_back(o->intensity[c]);
    floor[c] = std::max(MedianInPlace(values), 1e-6);
  }
  return floor;
}

// cos_theta of every observation as the fit sees it for one candidate rig. In air, shaded with the
// candidate (lib/model/shading.h): where a flash beside the lens is, is what shading needs, and how it shades
// the tilted targets is what tells it. In water, as the observations were shaded (from the camera while the
// rig is a guess): shaded with each candidate instead, the Blender clear boards chose isotropic lights at
// +-0.4 m rather than +-0.6 m and the worst ColorChecker patch went from 5.75 to 9.72 pp, since isotropic
// candidates do not model the spots' cones that shade its tilted patches. An observation without a normal
// keeps its own cos_theta.
struct RigCosines {
  std::vector<double> known, first, second;
};

RigCosines CosinesFor(const LightRig& rig, const FitData& data, bool shade_with_rig) {
  Shading shading;
  shading.rig = rig;
  const auto cosine = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double own) {
    return normal.isZero() || !shade_with_rig ? own : shading.Cosine(point, normal);
  };
  RigCosines cosines;
  for (const KnownColorObservation* o : data.known) cosines.known.push_back(cosine(o->point_in_cam, o->normal_in_cam, o->cos_theta));
  for (const CorrespondenceObservation* o : data.correspondences) {
    cosines.first.push_back(cosine(o->first.point_in_cam, o->first.normal_in_cam, o->first.cos_theta));
    cosines.second.push_back(cosine(o->second.point_in_cam, o->second.normal_in_cam, o->second.cos_theta));
  }
  return cosines;
}

// The simulator's alpha and beta at every observation for one water (one value per channel).
struct ModelSamples {
  std::vector<Eigen::Vector3f> known_alpha, known_beta;
  std::vector<Eigen::Vector3f> first_alpha, first_beta, second_alpha, second_beta;
  std::vector<Eigen::Vector3f> pure_water_beta;
};

Water WaterOfAttenuation(const Eigen::Vector3d& attenuation, const Water& start) {
  const Eigen::Vector3d start_attenuation = start.Attenuation();
  Water water;
  water.anisotropy_g = start.anisotropy_g;
  for (int c = 0; c < 3; ++c) {
    const double albedo = start_attenuation[c] > 0 ? start.scattering[c] / start_attenuation[c] : 0.5;
    water.scattering[c] = attenuation[c] * albedo;
    water.absorption[c] = attenuation[c] - water.scattering[c];
  }
  return water;
}

SimulatorOptions SingleThreaded() {
  SimulatorOptions options;
  options.num_threads = 1;  // the search is parallel over waters instead
  options.backscatter_steps = 32;
  return options;
}

class ModelRenderer {
 public:
  ModelRenderer(const LightRig& rig, const Camera& camera, const FrustumLutGrid& grid, const Water& start)
      : rig_(rig), camera_(camera), grid_(grid), start_(start) {}

  // The simulator's LUT for a water of `attenuation`; with `far`, beta of every slab is the backscatter
  // to the simulator's pure-water range along the node's ray (what a pure-water pixel sees).
  FrustumLut Render(const Eigen::Vector3d& attenuation, bool far) const {
    const Simulator simulator(no_geometry_, rig_, WaterOfAttenuation(attenuation, start_),
                              SurfaceAlbedo::Constant(Eigen::Vector3d::Ones()), SingleThreaded());
    FrustumLut lut = simulator.TrueLut(camera_, grid_);
    if (!far) return lut;
    const double range = SimulatorOptions().max_range;
    for (int j = 0; j < grid_.NodesY(); ++j) {
      for (int i = 0; i < grid_.NodesX(); ++i) {
        const Eigen::Vector3d beta = simulator.Backscatter(camera_.CamFromImg(lut.NodePixel(i, j)).normalized(), range);
        for (int k = 0; k < grid_.nz; ++k) lut.node(i, j, k).beta = beta;
      }
    }
    return lut;
  }

  ModelSamples Sample(const Eigen::Vector3d& attenuation, const FitData& data) const {
    const FrustumLut near = Render(attenuation, false);
    ModelSamples samples;
    const auto look = [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point, std::vector<Eigen::Vector3f>* alpha,
                          std::vector<Eigen::Vector3f>* beta) {
      const LutNode node = near.Lookup(pixel.x(), pixel.y(), point.z());
      alpha->push_back(node.alpha.cast<float>());
      beta->push_back(node.beta.cast<float>());
    };
    for (const KnownColorObservation* o : data.known) look(o->pixel, o->point_in_cam, &samples.known_alpha, &samples.known_beta);
    for (const CorrespondenceObservation* o : data.correspondences) {
      look(o->first.pixel, o->first.point_in_cam, &samples.first_alpha, &samples.first_beta);
      look(o->second.pixel, o->second.point_in_cam, &samples.second_alpha, &samples.second_beta);
    }
    if (!data.pure_water.empty()) {
      const FrustumLut far_lut = Render(attenuation, true);
      for (const PureWaterObservation* o : data.pure_water) {
        samples.pure_water_beta.push_back(far_lut.Lookup(o->pixel.x(), o->pixel.y(), grid_.z_far).beta.cast<float>());
      }
    }
    return samples;
  }

 private:
  const Mesh no_geometry_;
  const LightRig& rig_;
  const Camera& camera_;
  FrustumLutGrid grid_;
  const Water& start_;
};

struct ChannelFit {
  double signal_scale = 0.0, backscatter_scale = 0.0;
  double cost = std::numeric_limits<double>::infinity();
  double weight_sum = 0.0;
};

// The weighted least-squares (k, s >= 0) for one channel, alpha from `a`, beta from `b`, shaded as `cosines`.
ChannelFit FitScales(const FitData& data, const RigCosines& cosines, const ModelSamples& a, const ModelSamples& b,
                     int c) {
  // Normal equations of  sum w (k P + s B - I)^2  and  sum w (R - s Q)^2.
  double pp = 0, pb = 0, bb = 0, pi = 0, bi = 0, ii = 0, weight_sum = 0;
  const auto relative = [&](double intensity) { return 1.0 / std::pow(std::max(intensity, 0.0) + data.floor[c], 2); };
  for (std::size_t n = 0; n < data.known.size(); ++n) {
    const KnownColorObservation& o = *data.known[n];
    const double w = relative(o.intensity[c]);
    const double p = a.known_alpha[n][c] * cosines.known[n] * o.albedo[c], q = b.known_beta[n][c], y = o.intensity[c];
    pp += w * p * p, pb += w * p * q, bb += w * q * q, pi += w * p * y, bi += w * q * y, ii += w * y * y;
    weight_sum += 1.0;
  }
  for (std::size_t n = 0; n < data.correspondences.size(); ++n) {
    const CorrespondenceObservation& o = *data.correspondences[n];
    const double u = a.second_alpha[n][c] * cosines.second[n], v = a.first_alpha[n][c] * cosines.first[n];
    const double norm = 0.5 * (u + v);
    if (!(norm > 0)) continue;
    const double w = relative(0.5 * (o.first.intensity[c] + o.second.intensity[c]));
    const double r = (u * o.first.intensity[c] - v * o.second.intensity[c]) / norm;
    const double q = (u * b.first_beta[n][c] - v * b.second_beta[n][c]) / norm;
    bb += w * q * q, bi += w * q * r, ii += w * r * r;
    weight_sum += 1.0;
  }
  for (std::size_t n = 0; n < data.pure_water.size(); ++n) {
    const PureWaterObservation& o = *data.pure_water[n];
    const double w = relative(o.intensity[c]) * o.weight;
    const double q = b.pure_water_beta[n][c], y = o.intensity[c];
    bb += w * q * q, bi += w * q * y, ii += w * y * y;
    weight_sum += o.weight;
  }
  ChannelFit fit;
  fit.weight_sum = weight_sum;
  const auto cost = [&](double k, double s) { return ii + k * k * pp + s * s * bb + 2 * k * s * pb - 2 * k * pi - 2 * s * bi; };
  if (data.known.empty()) {
    // k does not enter; it is set afterwards from the grey-world albedo.
    fit.backscatter_scale = bb > 0 ? std::max(bi / bb, 0.0) : 0.0;
    fit.signal_scale = 0.0;  // set afterwards by GreyWorldSignalScale
    fit.cost = cost(0.0, fit.backscatter_scale);
    return fit;
  }
  const double det = pp * bb - pb * pb;
  double k = det > 0 ? (pi * bb - bi * pb) / det : 0.0, s = det > 0 ? (bi * pp - pi * pb) / det : 0.0;
  if (!(det > 0) || !(s >= 0.0) || !(k >= 0.0)) {
    // On a bound, or one of the two unseen (in air nothing sees backscatter): the better of s = 0 and k = 0.
    const double k_only = pp > 0 ? std::max(pi / pp, 0.0) : 0.0, s_only = bb > 0 ? std::max(bi / bb, 0.0) : 0.0;
    if (cost(k_only, 0.0) <= cost(0.0, s_only)) k = k_only, s = 0.0;
    else k = 0.0, s = s_only;
  }
  fit.signal_scale = k;
  fit.backscatter_scale = s;
  fit.cost = std::max(cost(k, s), 0.0);
  return fit;
}

// Without known colours: k so the correspondences' views restore, on average, to the grey-world albedo.
double GreyWorldSignalScale(const FitData& data, const RigCosines& cosines, const ModelSamples& a,
                            const ModelSamples& b, int c, double s, double grey_world) {
  double signal = 0.0, model = 0.0;
  for (std::size_t n = 0; n < data.correspondences.size(); ++n) {
    const CorrespondenceObservation& o = *data.correspondences[n];
    signal += (o.first.intensity[c] - s * b.first_beta[n][c]) + (o.second.intensity[c] - s * b.second_beta[n][c]);
    model += a.first_alpha[n][c] * cosines.first[n] + a.second_alpha[n][c] * cosines.second[n];
  }
  return model > 0 && signal > 0 ? signal / model / grey_world : 0.0;
}

struct Best {
  Eigen::Vector3d signal = Eigen::Vector3d::Zero(), backscatter = Eigen::Vector3d::Zero();
  std::array<ChannelFit, 3> fit;
};

// The best pair per channel among alpha from `signal_samples[i]` and beta from `backscatter_samples[j]`,
// whose attenuations per channel are `signal_attenuations[i]`, `backscatter_attenuations[j]`.
void SearchPairs(const FitData& data, const RigCosines& cosines, const std::vector<ModelSamples>& signal_samples,
                 const std::vector<Eigen::Vector3d>& signal_attenuations,
                 const std::vector<ModelSamples>& backscatter_samples,
                 const std::vector<Eigen::Vector3d>& backscatter_attenuations, int num_threads, Best* best) {
  ParallelFor(3, num_threads, [&](std::size_t channel) {
    const int c = static_cast<int>(channel);
    for (std::size_t i = 0; i < signal_samples.size(); ++i) {
      for (std::size_t j = 0; j < backscatter_samples.size(); ++j) {
        const ChannelFit fit = FitScales(data, cosines, signal_samples[i], backscatter_samples[j], c);
        // Ties (a constraint that does not see one of the two) go to the first, lowest attenuation.
        if (fit.cost < best->fit[channel].cost * (1.0 - 1e-12)) {
          best->fit[channel] = fit;
          best->signal[c] = signal_attenuations[i][c];
          best->backscatter[c] = backscatter_attenuations[j][c];
        }
      }
    }
  });
}

// Renders the simulator for one rig on the coarse search grid, at many waters in parallel.
class WaterSearch {
 public:
  WaterSearch(const FitData& data, const LightRig& rig, const Camera& camera, const FrustumLutGrid& coarse,
              const WaterPriorOptions& options)
      : data_(data), cosines_(CosinesFor(rig, data, options.start.IsAir())), renderer_(rig, camera, coarse, options.start), options_(options) {}

  std::vector<ModelSamples> SampleAll(const std::vector<Eigen::Vector3d>& attenuations) const {
    std::vector<ModelSamples> samples(attenuations.size());
    ParallelFor(attenuations.size(), options_.num_threads,
                [&](std::size_t i) { samples[i] = renderer_.Sample(attenuations[i], data_); });
    return samples;
  }

  // The best pair per channel over the global grid of attenuations (in air, no attenuation).
  Best Global() const {
    std::vector<Eigen::Vector3d> global;
    if (options_.start.IsAir()) {
      global.push_back(Eigen::Vector3d::Zero());
    } else {
      for (double value : GlobalAttenuations()) global.push_back(Eigen::Vector3d::Constant(value));
    }
    const std::vector<ModelSamples> samples = SampleAll(global);
    Best best;
    SearchPairs(data_, cosines_, samples, global, samples, global, options_.num_threads, &best);
    if (options_.start.IsAir()) SetGreyWorldSignalScale(samples.front(), samples.front(), &best);
    return best;
  }

  // Improves `best` over 2 x kLocalSteps + 1 steps across the global spacing on either side of each
  // channel's best (in air there is nothing to refine); without known colours, then sets k from the
  // grey-world albedo.
  void Refine(Best* best) const {
    if (options_.start.IsAir()) return;
    const std::vector<double> values = GlobalAttenuations();
    const auto spacing_at = [&](double value) {
      const auto above = std::upper_bound(values.begin(), values.end(), value + 1e-9);
      return above == values.end() ? values.back() - values[values.size() - 2] : *above - value;
    };
    const auto local = [&](const Eigen::Vector3d& centre) {
      std::vector<Eigen::Vector3d> around;
      for (int m = -kLocalSteps; m <= kLocalSteps; ++m) {
        Eigen::Vector3d value;
        for (int c = 0; c < 3; ++c) value[c] = std::max(0.0, centre[c] + spacing_at(centre[c]) * m / kLocalSteps);
        around.push_back(value);
      }
      return around;
    };
    const std::vector<Eigen::Vector3d> signal = local(best->signal), backscatter = local(best->backscatter);
    SearchPairs(data_, cosines_, SampleAll(signal), signal, SampleAll(backscatter), backscatter, options_.num_threads,
                best);
    if (data_.known.empty()) {
      SetGreyWorldSignalScale(renderer_.Sample(best->signal, data_), renderer_.Sample(best->backscatter, data_), best);
    }
  }

 private:
  // Without known colours, k from the grey-world albedo (alpha from `a`, beta from `b`).
  void SetGreyWorldSignalScale(const ModelSamples& a, const ModelSamples& b, Best* best) const {
    if (!data_.known.empty()) return;
    for (int c = 0; c < 3; ++c) {
      best->fit[c].signal_scale = GreyWorldSignalScale(data_, cosines_, a, b, c, best->fit[c].backscatter_scale,
                                                       options_.grey_world_albedo[c]);
    }
  }

  const FitData& data_;
  const RigCosines cosines_;
  const ModelRenderer renderer_;
  const WaterPriorOptions& options_;
};

// The rig with its lights' beams replaced by a cosine-power profile of `exponent` along +z (0: isotropic).
LightRig WithBeam(const LightRig& rig, double exponent) {
  LightRig beamed = rig;
  for (Light& light : beamed.lights) {
    light.profile = exponent > 0 ? BeamProfile::kCosinePower : BeamProfile::kIsotropic;
    light.exponent = exponent;
  }
  return beamed;
}

// Rigs tried when the rig is a guess, in water: the light split into a symmetric pair 0.1 to 0.6 m either
// side along x or y (isotropic), and the guess with cosine-power beams.
std::vector<LightRig> CandidateRigs(const LightRig& guess) {
  std::vector<LightRig> rigs;
  for (double exponent : kBeamExponents) rigs.push_back(WithBeam(guess, exponent));
  for (int axis = 0; axis < 2; ++axis) {
    for (double offset : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}) {
      LightRig pair;
      for (double side : {-1.0, 1.0}) {
        for (Light light : guess.lights) {
          light.position_in_cam[axis] += side * offset;
          light.name = std::string(side < 0 ? "-" : "+") + (axis == 0 ? "x" : "y") + " of the fitted pair";
          pair.lights.push_back(light);
        }
      }
      rigs.push_back(pair);
    }
  }
  return rigs;
}

// Rigs tried in air when the rig is a guess: its light (a flash) moved by `step` over a square of
// half-size `half_size` around `centre` across the camera's x and y, isotropic and with every beam.
std::vector<LightRig> CandidateFlashes(const LightRig& guess, const Eigen::Vector3d& centre, double half_size,
                                       double step) {
  std::vector<LightRig> rigs;
  const int steps = static_cast<int>(std::lround(half_size / step));
  for (int iy = -steps; iy <= steps; ++iy) {
    for (int ix = -steps; ix <= steps; ++ix) {
      for (double exponent : {0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0}) {
        LightRig rig = WithBeam(guess, exponent);
        for (Light& light : rig.lights) {
          light.position_in_cam = centre + Eigen::Vector3d(ix * step, iy * step, 0.0);
          light.name = "fitted flash";
        }
        rigs.push_back(rig);
      }
    }
  }
  return rigs;
}

double TotalCost(const Best& best) {
  double total = 0.0;
  for (const ChannelFit& fit : best.fit) total += fit.weight_sum > 0 ? fit.cost / fit.weight_sum : 0.0;
  return total;
}

// The candidate that fits best, or `*rig` itself when none does better than `*best`. Candidates are
// searched in parallel, each on one thread, and chosen in their order: the result does not depend on the
// thread count.
void ChooseRig(const FitData& data, const std::vector<LightRig>& candidates, const Camera& camera,
               const FrustumLutGrid& coarse, const WaterPriorOptions& options, LightRig* rig, Best* best) {
  WaterPriorOptions one_thread = options;
  one_thread.num_threads = 1;
  std::vector<Best> fits(candidates.size());
  ParallelFor(candidates.size(), options.num_threads, [&](std::size_t i) {
    fits[i] = WaterSearch(data, candidates[i], camera, coarse, one_thread).Global();
  });
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (TotalCost(fits[i]) < TotalCost(*best)) *best = fits[i], *rig = candidates[i];
  }
}

}  // namespace

WaterPrior FitWaterPrior(const ObservationSet& observations, const LightRig& rig, const Camera& camera,
                         const FrustumLutGrid& grid, const WaterPriorOptions& options) {
  if (observations.known_colors.empty() && observations.correspondences.empty()) {
    throw std::invalid_argument("the water prior needs known colours or correspondences");
  }
  if (observations.known_colors.empty() && !(options.grey_world_albedo.minCoeff() > 0.0)) {
    throw std::invalid_argument("without known colours the water prior needs a grey-world albedo");
  }
  FitData data;
  data.known = Subsample(observations.known_colors);
  data.correspondences = Subsample(observations.correspondences);
  data.pure_water = Subsample(observations.pure_water);
  data.floor = NoiseFloor(data);

  // The search runs on a coarse grid (the model is smooth); the prior itself on the calibration grid.
  FrustumLutGrid coarse = grid;
  coarse.nx = std::min(grid.nx, 16);
  coarse.ny = std::min(grid.ny, 12);
  // With a guessed rig, the rig is chosen on the global grid of waters, then refined with its own.
  LightRig fitted_rig = rig;
  Best best = WaterSearch(data, rig, camera, coarse, options).Global();
  if (options.fit_beam && !options.start.IsAir()) {
    ChooseRig(data, CandidateRigs(rig), camera, coarse, options, &fitted_rig, &best);
  } else if (options.fit_beam && rig.lights.size() == 1) {
    const Eigen::Vector3d guess = rig.lights[0].position_in_cam;
    ChooseRig(data, CandidateFlashes(rig, guess, kFlashSearchHalfSize, kFlashCoarseStep), camera, coarse, options,
              &fitted_rig, &best);
    ChooseRig(data, CandidateFlashes(rig, fitted_rig.lights[0].position_in_cam, kFlashCoarseStep, kFlashFineStep),
              camera, coarse, options, &fitted_rig, &best);
  }
  WaterSearch(data, fitted_rig, camera, coarse, options).Refine(&best);

  WaterPrior prior;
  prior.in_air = options.start.IsAir();
  prior.signal_attenuation = best.signal;
  prior.backscatter_attenuation = best.backscatter;
  prior.rig = fitted_rig;
  for (int c = 0; c < 3; ++c) {
    prior.signal_scale[c] = best.fit[c].signal_scale;
    prior.backscatter_scale[c] = best.fit[c].backscatter_scale;
    prior.relative_rms[c] = best.fit[c].weight_sum > 0 ? std::sqrt(best.fit[c].cost / best.fit[c].weight_sum) : 0.0;
  }
  const ModelRenderer renderer(fitted_rig, camera, grid, options.start);
  const FrustumLut signal = renderer.Render(best.signal, false), backscatter = renderer.Render(best.backscatter, false);
  prior.lut = FrustumLut(grid);
  for (int n = 0; n < grid.NumNodes(); ++n) {
    prior.lut.node(n).alpha = signal.node(n).alpha.cwiseProduct(prior.signal_scale);
    prior.lut.node(n).beta = backscatter.node(n).beta.cwiseProduct(prior.backscatter_scale);
  }
  prior.backscatter_reached = FrustumLut(grid);
  if (!prior.in_air) {
    const FrustumLut open_water = renderer.Render(best.backscatter, true);
    for (int n = 0; n < grid.NumNodes(); ++n) {
      const Eigen::Vector3d near = backscatter.node(n).beta, far = open_water.node(n).beta;
      for (int c = 0; c < 3; ++c) {
        prior.backscatter_reached.node(n).beta[c] = far[c] > 0.0 ? std::clamp(near[c] / far[c], 0.0, 1.0) : 0.0;
      }
    }
  }
  return prior;
}

std::string DescribeWaterPrior(const WaterPrior& prior) {
  char text[400];
  std::snprintf(text, sizeof(text),
                "attenuation of the signal %.3f %.3f %.3f, of backscatter %.3f %.3f %.3f per m (r g b); ",
                prior.signal_attenuation.x(), prior.signal_attenuation.y(), prior.signal_attenuation.z(),
                prior.backscatter_attenuation.x(), prior.backscatter_attenuation.y(),
                prior.backscatter_attenuation.z());
  std::string description = prior.in_air ? "in air; " : text;
  description += std::to_string(prior.rig.lights.size()) + " light(s)";
  for (std::size_t l = 0; l < prior.rig.lights.size(); ++l) {
    const Light& light = prior.rig.lights[l];
    std::snprintf(text, sizeof(text), "%s (%.2f, %.2f, %.2f) m %s", l == 0 ? " at" : ",", light.position_in_cam.x(),
                  light.position_in_cam.y(), light.position_in_cam.z(), BeamProfileName(light.profile));
    description += text;
    if (light.profile == BeamProfile::kCosinePower) {
      std::snprintf(text, sizeof(text), "^%.1f", light.exponent);
      description += text;
    }
  }
  return description;
}

}  // namespace lutex
