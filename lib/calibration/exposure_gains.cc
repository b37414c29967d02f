#include "lib/calibration/exposure_gains.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>


namespace lutex {

namespace {

// Below this a known colour's prediction is taken as nothing (its log would be -inf).
constexpr double kSmallestPrediction = 1e-6;
// Weight of the pull towards gain 1 (see below), against data residuals of weight 1.
constexpr double kPriorWeight = 1e-3;
// The first phase's loss scale (log units): least squares for every plausible mismatch.
constexpr double kWideLossScale = 1.0;
// sigma = 1.4826 MAD for Gaussian residuals; a Cauchy loss of scale 2.385 sigma is 95 % efficient there.
constexpr double kMadToSigma = 1.4826;
constexpr double kCauchyEfficiencyFactor = 2.385;
// A Gauss-Newton phase ends when no log gain moves more than this.
constexpr double kConverged = 1e-7;

// One residual: r = log(I) - s_image - log(prediction), with its derivatives by s_image (always -1) and by
// s_other (d_other), `other` the other view's image of a correspondence (-1 for a known colour).
struct Term {
  int image = -1, other = -1;
  double residual = 0.0, d_other = 0.0;
};

// Calls visit(term) for every usable channel observation at the log gains `log_gains`: each known colour
// against the LUT's prediction for its albedo, each view of a correspondence against what the other view
// restores the point to. Correspondences beyond options.max_correspondences_per_pair for their pair, and
// known colours beyond options.max_known_colors_per_image for their image, are not visited (the same ones
// at every call).
template <typename Visit>
void ForEachTerm(const ObservationSet& observations, const FrustumLut& lut, const ExposureGainOptions& options,
                 const std::vector<double>& log_gains, Visit&& visit) {
  const std::size_t num_images = observations.images.size();
  const auto valid_image = [&](int image) { return image >= 0 && static_cast<std::size_t>(image) < num_images; };
  const auto usable = [&](double intensity, double beta) {
    return intensity >= options.min_intensity && intensity - beta >= options.min_signal_fraction * intensity;
  };
  std::vector<int> known_per_image(num_images, 0);
  for (const KnownColorObservation& o : observations.known_colors) {
    if (!valid_image(o.image) || known_per_image[static_cast<std::size_t>(o.image)] >= options.max_known_colors_per_image) continue;
    const LutNode node = lut.Lookup(o.pixel.x(), o.pixel.y(), o.point_in_cam.z());
    for (int c = 0; c < 3; ++c) {
      const double predicted = node.alpha[c] * o.cos_theta * o.albedo[c] + node.beta[c];
      if (!(o.weight[c] > 0.0) || !usable(o.intensity[c], node.beta[c]) || !(predicted > kSmallestPrediction)) continue;
      ++known_per_image[static_cast<std::size_t>(o.image)];
      visit(Term{o.image, -1, std::log(o.intensity[c] / predicted) - log_gains[static_cast<std::size_t>(o.image)], 0.0});
    }
  }
  std::map<std::pair<int, int>, int> per_pair;
  for (const CorrespondenceObservation& o : observations.correspondences) {
    if (!valid_image(o.first.image) || !valid_image(o.second.image) || o.first.image == o.second.image) continue;
    int& pair_count = per_pair[std::minmax(o.first.image, o.second.image)];
    if (pair_count >= options.max_correspondences_per_pair) continue;
    const LutNode first = lut.Lookup(o.first.pixel.x(), o.first.pixel.y(), o.first.point_in_cam.z());
    const LutNode second = lut.Lookup(o.second.pixel.x(), o.second.pixel.y(), o.second.point_in_cam.z());
    bool counted = false;
    for (int c = 0; c < 3; ++c) {
      const double first_alpha_cos = first.alpha[c] * o.first.cos_theta;
      const double second_alpha_cos = second.alpha[c] * o.second.cos_theta;
      if (!(o.weight[c] > 0.0) || !(first_alpha_cos > 0.0) || !(second_alpha_cos > 0.0) ||
          !usable(o.first.intensity[c], first.beta[c]) || !usable(o.second.intensity[c], second.beta[c])) {
        continue;
      }
      counted = true;
      // Both directions: each view against the other's albedo.
      const auto term = [&](const SurfaceView& view, double alpha_cos, double beta, const SurfaceView& other,
                            double other_alpha_cos, double other_beta) {
        // At the current gains the other view must still be mostly signal (as both were at gain 1), else
        // its albedo, and the prediction from it, say nothing.
        const double other_signal = other.intensity[c] * std::exp(-log_gains[static_cast<std::size_t>(other.image)]);
        if (other_signal - other_beta < options.min_signal_fraction * other_signal) return;
        const double predicted = alpha_cos * (other_signal - other_beta) / other_alpha_cos + beta;
        visit(Term{view.image, other.image,
                   std::log(view.intensity[c]) - log_gains[static_cast<std::size_t>(view.image)] - std::log(predicted),
                   alpha_cos * other_signal / (other_alpha_cos * predicted)});
      };
      term(o.first, first_alpha_cos, first.beta[c], o.second, second_alpha_cos, second.beta[c]);
      term(o.second, second_alpha_cos, second.beta[c], o.first, first_alpha_cos, first.beta[c]);
    }
    if (counted) ++pair_count;
  }
}

// The median |residual| over the terms of images with a gain, from a histogram (bins of 1e-5 up to 1;
// beyond counts in the last): memory does not grow with the observations.
double MedianAbsoluteResidual(const ObservationSet& observations, const FrustumLut& lut,
                              const ExposureGainOptions& options, const std::vector<double>& log_gains,
                              const std::vector<int>& unknown) {
  constexpr int kBins = 100000;
  std::vector<std::size_t> histogram(kBins, 0);
  std::size_t count = 0;
  ForEachTerm(observations, lut, options, log_gains, [&](const Term& term) {
    if (unknown[static_cast<std::size_t>(term.image)] < 0) return;
    ++histogram[static_cast<std::size_t>(std::min(std::abs(term.residual) * kBins, kBins - 1.0))];
    ++count;
  });
  std::size_t seen = 0;
  for (int bin = 0; bin < kBins; ++bin) {
    seen += histogram[static_cast<std::size_t>(bin)];
    if (2 * seen >= count) return (bin + 0.5) / kBins;
  }
  return 1.0;
}

// Groups of images linked by correspondences (union-find).
class ImageGroups {
 public:
  explicit ImageGroups(std::size_t count) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t Root(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(std::size_t a, std::size_t b) { parent_[Root(a)] = Root(b); }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace

void ExposureGainOptions::Check() const {
  if (!(min_intensity > 0.0)) throw std::invalid_argument("exposure gains: min_intensity must be positive");
  if (!(min_signal_fraction > 0.0 && min_signal_fraction < 1.0)) {
    throw std::invalid_argument("exposure gains: min_signal_fraction must be in (0, 1)");
  }
  if (max_iterations < 1 || max_known_colors_per_image < 1 || max_correspondences_per_pair < 1) {
    throw std::invalid_argument("exposure gains: iterations and observation counts must be at least 1");
  }
}

ExposureGains FitExposureGains(const ObservationSet& observations, const FrustumLut& lut,
                               const ExposureGainOptions& options) {
  options.Check();
  const std::size_t num_images = observations.images.size();
  ExposureGains result;
  result.gains.assign(num_images, 1.0);
  result.num_residuals.assign(num_images, 0);
  result.fixed_by_known_colors.assign(num_images, false);
  std::vector<double> log_gains(num_images, 0.0);

  // Which images the data reach, and how they group. Only images in a group with correspondences get a
  // gain: an image that only shows known colours (a board at one distance) would have its gain trade
  // with the LUT's fall-off at that distance.
  ImageGroups groups(num_images);
  std::vector<bool> has_correspondences(num_images, false);
  ForEachTerm(observations, lut, options, log_gains, [&](const Term& term) {
    ++result.num_residuals[static_cast<std::size_t>(term.image)];
    if (term.other < 0) result.fixed_by_known_colors[static_cast<std::size_t>(term.image)] = true;
    if (term.other >= 0) {
      groups.Join(static_cast<std::size_t>(term.image), static_cast<std::size_t>(term.other));
      has_correspondences[static_cast<std::size_t>(term.image)] = true;
    }
  });
  std::vector<bool> group_has_correspondences(num_images, false);
  for (std::size_t i = 0; i < num_images; ++i) {
    if (has_correspondences[i]) group_has_correspondences[groups.Root(i)] = true;
  }
  std::vector<int> unknown(num_images, -1);  // image -> its unknown in the normal equations
  int num_unknowns = 0;
  for (std::size_t i = 0; i < num_images; ++i) {
    if (result.num_residuals[i] > 0 && group_has_correspondences[groups.Root(i)]) {
      unknown[i] = num_unknowns++;
    } else {
      result.num_residuals[i] = 0;
      result.fixed_by_known_colors[i] = false;
    }
  }
  if (num_unknowns == 0) return result;

  // Iteratively reweighted Gauss-Newton on the log gains, in two phases of at most options.max_iterations
  // each, ending when no log gain moves more than kConverged: first with a loss so wide that it is least
  // squares for every plausible mismatch, then with a Cauchy loss (weights 1 / (1 + (r/a)^2)) whose scale
  // a = 2.385 sigma (95 % efficiency for Gaussian residuals) follows the residuals' own spread there,
  // sigma = 1.4826 median |r|: the data say how large an honest mismatch is (noise, and the LUT's own
  // errors), and only what lies well beyond counts less. A faint pull of every gain towards 1 is added:
  // where nothing fixes the common scale of a group (no known colours, and in air no backscatter either)
  // it picks the solution nearest gain 1 and keeps the normal equations regular; elsewhere its effect is
  // below 1e-6 of a gain.
  double loss_scale = kWideLossScale;
  for (int phase = 0; phase < 2; ++phase) {
    if (phase == 1) loss_scale = kCauchyEfficiencyFactor * kMadToSigma * MedianAbsoluteResidual(observations, lut, options, log_gains, unknown);
    if (!(loss_scale > 0.0)) break;  // every residual 0: nothing left to weigh
    for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
      std::map<std::pair<int, int>, double> hessian;  // upper triangle, by unknowns
      Eigen::VectorXd gradient = Eigen::VectorXd::Zero(num_unknowns);
      ForEachTerm(observations, lut, options, log_gains, [&](const Term& term) {
        const double weight = 1.0 / (1.0 + (term.residual / loss_scale) * (term.residual / loss_scale));
        const int a = unknown[static_cast<std::size_t>(term.image)];
        if (a < 0) return;  // a known colour of an image without a gain
        // Derivatives: -1 by the term's own log gain, d_other by the other's.
        hessian[{a, a}] += weight;
        gradient[a] -= weight * term.residual;
        if (term.other >= 0) {
          const int b = unknown[static_cast<std::size_t>(term.other)];
          hessian[{std::min(a, b), std::max(a, b)}] -= weight * term.d_other;
          hessian[{b, b}] += weight * term.d_other * term.d_other;
          gradient[b] += weight * term.d_other * term.residual;
        }
      });
      std::vector<Eigen::Triplet<double>> triplets;
      for (std::size_t i = 0; i < num_images; ++i) {
        if (unknown[i] < 0) continue;
        hessian[{unknown[i], unknown[i]}] += kPriorWeight * kPriorWeight;
        gradient[unknown[i]] += kPriorWeight * kPriorWeight * log_gains[i];
      }
      for (const auto& [entry, value] : hessian) {
        triplets.emplace_back(entry.first, entry.second, value);
        if (entry.first != entry.second) triplets.emplace_back(entry.second, entry.first, value);
      }
      Eigen::SparseMatrix<double> normal(num_unknowns, num_unknowns);
      normal.setFromTriplets(triplets.begin(), triplets.end());
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
      const Eigen::VectorXd step = solver.solve(-gradient);
      // The prior makes the matrix positive definite: a failure here is a bug or non-finite data.
      if (solver.info() != Eigen::Success || !step.allFinite()) {
        throw std::runtime_error("exposure gains: the normal equations have no finite solution");
      }
      double largest = 0.0;
      for (std::size_t i = 0; i < num_images; ++i) {
        if (unknown[i] < 0) continue;
        log_gains[i] += step[unknown[i]];
        largest = std::max(largest, std::abs(step[unknown[i]]));
      }
      if (largest < kConverged) break;
    }
  }

  // Groups without known colours: geometric mean 1.
  std::vector<bool> group_has_known_colors(num_images, false);
  std::vector<double> log_sum(num_images, 0.0);
  std::vector<std::size_t> count(num_images, 0);
  for (std::size_t i = 0; i < num_images; ++i) {
    if (result.num_residuals[i] == 0) continue;
    if (result.fixed_by_known_colors[i]) group_has_known_colors[groups.Root(i)] = true;
    log_sum[groups.Root(i)] += log_gains[i];
    ++count[groups.Root(i)];
  }
  for (std::size_t i = 0; i < num_images; ++i) {
    if (result.num_residuals[i] == 0) continue;
    const std::size_t root = groups.Root(i);
    const double shift = group_has_known_colors[root] ? 0.0 : log_sum[root] / static_cast<double>(count[root]);
    result.gains[i] = std::exp(log_gains[i] - shift);
    result.fixed_by_known_colors[i] = group_has_known_colors[root];
  }
  return result;
}

void DivideOutExposureGains(const std::vector<double>& gains, ObservationSet* observations) {
  if (gains.size() != observations->images.size()) {
    throw std::invalid_argument("exposure gains: one gain per observation image is needed");
  }
  const auto divide = [&](int image, Eigen::Vector3d* intensity) {
    if (image >= 0 && static_cast<std::size_t>(image) < gains.size()) *intensity /= gains[static_cast<std::size_t>(image)];
  };
  for (KnownColorObservation& o : observations->known_colors) divide(o.image, &o.intensity);
  for (PureWaterObservation& o : observations->pure_water) divide(o.image, &o.intensity);
  for (CorrespondenceObservation& o : observations->correspondences) {
    divide(o.first.image, &o.first.intensity);
    divide(o.second.image, &o.second.intensity);
  }
}

}  // namespace lutex
