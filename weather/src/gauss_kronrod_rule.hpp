// Gauss-Kronrod nodes and weights on [-1, 1] from Boost.Math's tables, with
// the embedded Gauss weights laid out per node, for the panel integrators of
// bulk_optics.cpp and contour_extinction.cpp (which need both sums of one set
// of evaluations, plus their own side quantities per node).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace attenuvis::weather::detail {

// abscissa[i] >= 0; node i > 0 stands for the pair +-abscissa[i].
struct Rule {
  std::vector<double> abscissa, kronrod_weight, gauss_weight;
  int points = 0;
};

template <unsigned N>
Rule make_rule() {
  using GK = boost::math::quadrature::gauss_kronrod<double, N>;
  using G = boost::math::quadrature::gauss<double, (N - 1) / 2>;
  Rule r;
  const auto& x = GK::abscissa();
  const auto& w = GK::weights();
  r.abscissa.assign(x.begin(), x.end());
  r.kronrod_weight.assign(w.begin(), w.end());
  // Boost stores the Kronrod abscissae with the embedded Gauss nodes at even
  // indices when the Gauss order is odd (0 is then a Gauss node) and at odd
  // indices otherwise; the Gauss weight of node i is G::weights()[i / 2]
  // (same layout as gauss_kronrod::integrate_non_adaptive_m1_1).
  r.gauss_weight.assign(x.size(), 0.0);
  unsigned first = (((N - 1) / 2) & 1) ? 0 : 1;
  for (unsigned i = first; i < x.size(); i += 2) r.gauss_weight[i] = G::weights()[i / 2];
  r.points = static_cast<int>(N);
  return r;
}

// The rule's 2n - 1 nodes on [-1, 1] in increasing order, each with its
// Kronrod and Gauss weight (0 at the Kronrod-only nodes): the layout the
// panel integrators visit (so S(0) is batched over neighbouring |x|).
struct OrderedNodes {
  std::vector<double> u, kronrod_weight, gauss_weight;
};
inline OrderedNodes ordered_nodes(const Rule& rule) {
  const std::size_t n = rule.abscissa.size(), count = 2 * n - 1;
  OrderedNodes out{std::vector<double>(count), std::vector<double>(count), std::vector<double>(count)};
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t slot : {n - 1 - i, n - 1 + i}) {
      out.u[slot] = slot < n - 1 ? -rule.abscissa[i] : rule.abscissa[i];
      out.kronrod_weight[slot] = rule.kronrod_weight[i];
      out.gauss_weight[slot] = rule.gauss_weight[i];
    }
  return out;
}

inline Rule rule_for(int points) {
  switch (points) {
    case 15: return make_rule<15>();
    case 21: return make_rule<21>();
    case 31: return make_rule<31>();
    case 41: return make_rule<41>();
    case 51: return make_rule<51>();
    case 61: return make_rule<61>();
    default:
      throw std::invalid_argument("Gauss-Kronrod order " + std::to_string(points) +
                                  " is not available (15, 21, 31, 41, 51 or 61)");
  }
}

}  // namespace attenuvis::weather::detail
