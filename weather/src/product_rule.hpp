// Gauss-Kronrod product integration of a piecewise-linear weight against a
// smooth function: the panel rule of a table's many short segments
// (segmented_contour.cpp).
//
// On one panel, u in [-1, 1], the integrand is w(u) f(u), where f is smooth
// (S(0) along a path well above the real axis) and w is a different linear
// polynomial alpha_s + beta_s x(u) on each sub-interval s (a table's segments
// continued to the path: they do not join off the axis, so w jumps at every
// breakpoint and no plain quadrature rule converges across them).  Product
// integration replaces f, and x f, by the polynomials that interpolate them
// at the rule's 2n + 1 Kronrod nodes, and integrates each against w exactly
// (Davis & Rabinowitz 1984, Methods of Numerical Integration, Sec. 2.5; the
// Legendre form keeps it well conditioned):
//
//   int w f du = sum_j f_j omega_j,  omega_j = sum_l C_lj (A_l + x_j B_l),
//   A_l = sum_s alpha_s int_s P_l du,  B_l = sum_s beta_s int_s P_l du,
//
// C the inverse of the Legendre-Vandermonde matrix P_l(u_j).  The same with
// the n embedded Gauss nodes gives the estimate |K - G|.  On a panel with no
// breakpoint inside, omega_j is the Gauss-Kronrod weight times w(x_j): the
// product rule is the panel rule, no less exact.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "gauss_kronrod_rule.hpp"

namespace attenuvis::weather::detail {

class ProductRule {
 public:
  // The rule's nodes in increasing u, in the order evaluate_path_panel
  // (contour_panel.hpp) lays them out.
  explicit ProductRule(const Rule& rule);

  // One sub-interval [u0, u1] of [-1, 1] and its weight alpha + beta x.
  struct Segment {
    double u0, u1;
    std::complex<double> alpha, beta;
  };

  // The weights omega_j of the Kronrod and of the Gauss sums (zero at the
  // Kronrod-only nodes) for the segments, x_j the path at the nodes; the
  // panel integral over [-1, 1] in u is sum_j f_j omega_j.
  void weights(const std::vector<Segment>& segments, const std::vector<std::complex<double>>& x,
               std::vector<std::complex<double>>& kronrod, std::vector<std::complex<double>>& gauss) const;

  std::size_t size() const { return node_.size(); }
  double node(std::size_t j) const { return node_[j]; }

 private:
  std::vector<double> node_;
  std::vector<std::size_t> gauss_slot_;          // the Gauss nodes among node_
  std::vector<double> kronrod_inverse_;          // C (size x size), row l = Legendre degree
  std::vector<double> gauss_inverse_;            // the same on the Gauss nodes (n x n)
};

}  // namespace attenuvis::weather::detail
