#pragma once

// The calibration's residuals, one channel at a time. Every LUT node is a parameter block of two values
// (alpha, beta) for the channel being solved. A lookup combines up to 8 nodes with weights from
// FrustumLut::Weights (alpha_weight for alpha, weight for beta).

#include <array>
#include <vector>

#include <ceres/ceres.h>

namespace lutex {

// Known colour, paper Eq. 5: w * (sum_i a_i alpha_i * cos_theta * rho + sum_i b_i beta_i - I).
struct KnownColorResidual {
  std::vector<double> alpha_weights;  // a_i, one per node block
  std::vector<double> beta_weights;   // b_i
  double shading_albedo;              // cos_theta * rho
  double intensity;                   // I
  double weight;                      // w

  template <typename T>
  bool operator()(T const* const* nodes, T* residual) const {
    T predicted = T(-intensity);
    for (std::size_t i = 0; i < alpha_weights.size(); ++i) {
      predicted += alpha_weights[i] * shading_albedo * nodes[i][0] + beta_weights[i] * nodes[i][1];
    }
    residual[0] = weight * predicted;
    return true;
  }

  static ceres::CostFunction* Create(std::vector<double> alpha_weights, std::vector<double> beta_weights,
                                     double shading_albedo, double intensity, double weight);
};

// Smoothness between two neighbouring nodes, paper Eq. 7: w * (s_a x_a - s_b x_b) for x = alpha
// (component 0) or beta (component 1). The scales let alpha be smoothed in the quantity the LUT
// interpolates (alpha z^2 with inverse-square interpolation, whose slabs differ by z^2); 1 otherwise.
struct SmoothnessResidual {
  int component;
  double weight;
  double scale_a = 1.0;
  double scale_b = 1.0;

  template <typename T>
  bool operator()(const T* node_a, const T* node_b, T* residual) const {
    residual[0] = weight * (scale_a * node_a[component] - scale_b * node_b[component]);
    return true;
  }

  static ceres::CostFunction* Create(int component, double weight, double scale_a = 1.0, double scale_b = 1.0);
};

// Pure water, paper Eq. 9, widened to a band. Above: w * (beta - I_pw) where beta exceeds I_pw (the
// paper's bound: backscatter up to a surface is less than to infinity). Below: w_short * (f I_pw - beta)
// where beta falls short of the fraction f of it that backscatter reaches at the slab's range (f from the
// water prior; f = 0 or w_short = 0: the paper's one-sided bound). beta = sum_i b_i beta_i.
struct PureWaterBoundResidual {
  std::vector<double> beta_weights;
  double intensity;
  double weight;
  double reached_fraction = 0.0;
  double short_weight = 0.0;

  template <typename T>
  bool operator()(T const* const* nodes, T* residual) const {
    T beta = T(0.0);
    for (std::size_t i = 0; i < beta_weights.size(); ++i) beta += beta_weights[i] * nodes[i][1];
    const T excess = beta - T(intensity);
    const T shortfall = T(reached_fraction * intensity) - beta;
    residual[0] = excess > T(0.0)      ? T(weight) * excess
                  : shortfall > T(0.0) ? T(short_weight) * shortfall
                                       : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(std::vector<double> beta_weights, double intensity, double weight,
                                     double reached_fraction = 0.0, double short_weight = 0.0);
};

// Correspondence (observations.h), one channel, over the union of the two views' nodes (Ceres takes a
// block once per residual, and the views often share nodes):
//   w * (alpha2 c2 (I1 - beta1) - alpha1 c1 (I2 - beta2)),  alpha_v = sum_i a_vi alpha_i, beta_v = sum_i b_vi beta_i.
struct CorrespondenceResidual {
  // Per node block: {a_1i, b_1i, a_2i, b_2i} (0 where the node is not one of the view's).
  std::vector<std::array<double, 4>> coefficients;
  double cos_theta_1, intensity_1, cos_theta_2, intensity_2;
  double weight;

  template <typename T>
  bool operator()(T const* const* nodes, T* residual) const {
    T alpha_1 = T(0.0), beta_1 = T(0.0), alpha_2 = T(0.0), beta_2 = T(0.0);
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
      alpha_1 += coefficients[i][0] * nodes[i][0];
      beta_1 += coefficients[i][1] * nodes[i][1];
      alpha_2 += coefficients[i][2] * nodes[i][0];
      beta_2 += coefficients[i][3] * nodes[i][1];
    }
    residual[0] = weight * (alpha_2 * cos_theta_2 * (intensity_1 - beta_1) - alpha_1 * cos_theta_1 * (intensity_2 - beta_2));
    return true;
  }

  static ceres::CostFunction* Create(std::vector<std::array<double, 4>> coefficients, double cos_theta_1,
                                     double intensity_1, double cos_theta_2, double intensity_2, double weight);
};

}  // namespace lutex
