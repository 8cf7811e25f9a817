// Which resonances of a nearly lossless sphere the size integral resolves,
// and a bound on what the others contribute (bulk_optics.hpp, "resonances").
//
// A pole x_p = x0 - i gamma of a_n or b_n with residue R (mie/resonances.hpp)
// adds to the sphere's coefficient c = R/(x - x_p) + h.  Every bulk integrand
// q(x) (efficiency times Q_sca-weighted angular factor) is linear or
// Hermitian-quadratic in the coefficients, so what the pole adds to
// int q w dx is made of two integrals,
//
//     I1 = int |R| / |x - x_p| (coherent: |int R/(x - x_p) dx| = pi |R|),
//     I2 = int |R|^2 / |x - x_p|^2 dx = pi |R|^2 / gamma,
//
// times the coefficient's factor in q and, for the cross terms, the size of
// the rest of the series.  With w the size weight in x (pi r^2 n(r) dr/dx, its
// largest value within x0 +- 1/2) and both integrals doubled (the rule that
// misses the peak still integrates part of its tails; w varies across it),
// I1 = 2 pi |R| w, I2 = 2 pi (|R|^2 / gamma) w, N = 2n + 1:
//
//   Q_ext = (2/x^2) sum N Re(a + b):        (2N / x0^2) I1
//   Q_sca = (2/x^2) sum N (|a|^2 + |b|^2):  (2N / x0^2) (I2 + 2 h I1),  h = 1 + |R|/gamma >= |h(x)|
//   Q_abs = Q_ext - Q_sca:                  the sum of the two
//   Q_back / 4 pi = |T|^2 / (4 pi x^2), T = sum N (-1)^n (a - b):
//                                           (N^2 I2 + 2 N T_max I1) / (4 pi x0^2),
//                                           T_max = x0 sqrt(Q_back,max) + N |R|/gamma
//   chi_l Q_sca = (1/x^2) int P_l (|S1|^2 + |S2|^2) dmu  (g Q_sca is l = 1): the pole's part of S1, S2
//       has int (|dS1|^2 + |dS2|^2) dmu = 2N |P|^2 (orthogonality of pi_n, tau_n, B&H Sec. 4.3), so by
//       Cauchy-Schwarz, |P_l| <= 1:          (2N I2 + 2 sqrt(2N) x0 sqrt(Q_sca,max') I1) / x0^2,
//       Q_sca,max' = Q_sca,max + (2N/x0^2)(|R|/gamma)^2; the expansion's coefficients (Wigner
//       kernels, |d| <= 1, products of S1 and S2) twice that times (2l + 1);
//   p(theta) Q_sca = 2 (|S1|^2 + |S2|^2) / x^2, |dS_j| <= N |P| / 2 (|pi_n|, |tau_n| <= n(n+1)/2):
//                                           (2 / x0^2) (N^2 I2 / 2 + N S_max I1),
//                                           S_max = x0 sqrt((p Q_sca)_max) + N |R|/gamma,
//
// the maxima sampled on the first pass's panel that holds x0 (a sample on the
// peak itself only raises them).  Brackets not located are charged the same
// with |R| replaced by their width estimate (>= |R|, resonances.hpp) and
// |R|/gamma by 1.
//
// A located pole of half-width >= 0.1 needs neither: the Gauss-Kronrod
// panels, no wider than 2 in x where resonances are (bulk_optics.hpp), sample
// its peak with two nodes or more.
//
// The plan: brackets are located in the order of their estimated bound
// relative to the allowed error, until the estimates of the rest sum to a
// quarter of it; located poles are resolved (a product-rule panel each,
// pole_rule.hpp) in the order of their bound until the unresolved ones sum to
// half of it.  A pole narrower than ~1e5 unit roundoffs of x cannot be
// resolved in double (its position is known to ~n eps x) and stays bounded;
// its |R| <= gamma makes that bound small.  When more poles would need a
// panel than max_resolved allows, those with the largest bounds get one and
// the rest stay bounded: the plan then says so (ResonancePlan::short_of), and
// the unresolved bound, reported as the resonance error, exceeds the share
// the tolerance gave it.
#pragma once

#include <atomic>
#include <complex>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "attenuvis/mie/resonances.hpp"
#include "bulk_components.hpp"

namespace attenuvis::weather::detail {

// What the first pass sampled near a resonance.
struct NearbySamples {
  double weight_x = 0;  // largest pi r^2 n(r) dr/dx within x0 +- 1/2
  Vec q_max;            // per component (Layout): largest |component / weight| on the panel holding x0
};

// A resolved resonance: the pole and the panel [x0 - reach, x0 + reach] its rule covers.
struct ResolvedResonance {
  mie::Resonance resonance;
  double reach = 0;
};

struct ResonancePlan {
  std::vector<ResolvedResonance> resolved;  // in increasing x0
  Vec unresolved_bound;                     // per component: what the other resonances may contribute
  std::size_t bracketed = 0, located = 0;
  // Empty when the unresolved bound is within the allowed error; else why not
  // (the budget, or poles narrower than double precision resolves).
  std::string short_of;
};

// The bound on what one resonance of order n at x0, |R| and half-width
// gamma contributes to each component, if no rule resolves it.
Vec resonance_bound(const Layout& layout, int order, double x0, double residue, double half_width,
                    const NearbySamples& near);

// The plan for index m over [x_lo, x_hi] in x, each component's allowed
// error in `allowed` (absolute), the breakpoints of the density (no panel
// crosses one) in x, at most max_resolved panels.  Checks `cancel`
// between batches of poles (Cancelled when set, cancel.hpp): a fog at 550 nm
// has ~1e4 of them.
ResonancePlan plan_resonances(std::complex<double> m, double x_lo, double x_hi, const Layout& layout,
                              const Vec& allowed, const std::vector<double>& breakpoints_x,
                              const std::function<NearbySamples(double)>& near, std::size_t max_resolved,
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace attenuvis::weather::detail
