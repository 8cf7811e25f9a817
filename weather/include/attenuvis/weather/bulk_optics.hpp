// Bulk optical properties of a size distribution: the integrals
//
//   sigma_ext = int Q_ext(x) pi r^2 n(r) dr,   x = 2 pi r / lambda      (van de Hulst 1957, Sec. 4.22)
//   sigma_sca, sigma_abs likewise;  albedo = sigma_sca / sigma_ext;
//   g = int g(x) Q_sca(x) pi r^2 n(r) dr / sigma_sca,
//
// and, when asked for in QuadratureSettings (nothing is computed that was not):
//   backscatter  beta_pi = int (Q_back(x) / 4 pi) pi r^2 n(r) dr   in 1/(m sr),
//                the volume backscatter coefficient (B&H 4.82 per sphere);
//                lidar ratio S = sigma_ext / beta_pi in sr;
//   moments      chi_l = int chi_l(x) Q_sca(x) pi r^2 n(r) dr / sigma_sca,
//                l = 0..L: the scattering-weighted Legendre moments of the
//                bulk phase function p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1,
//                chi_1 = g (legendre_moments.hpp: DISORT's PMOM(l) = chi_l);
//   phase        p(theta) = int p(theta; x) Q_sca(x) pi r^2 n(r) dr / sigma_sca
//                on an angle grid, normalised int p dOmega = 4 pi (p = 1 for
//                isotropic scattering; divide by 4 pi for 1/sr).
// Each is one more component of the same panel sums, with the same error terms
// (backscatter and phase relative to their own value, g absolute, chi_l
// relative to max(|chi_l|, 1e-3): relative down to 1e-3, absolute below).
//
// Tolerances: rel_tolerance governs sigma_ext, sigma_sca and sigma_abs (each
// relative to sigma_ext, so that the albedo is good to it as well);
// angular_tolerance (default max(rel_tolerance, 1e-6)) governs g, beta_pi,
// chi_l, p(theta) and the expansion.  The reported error of every quantity
// is at most its tolerance (or the function throws) and, by the analysis
// below, at least its actual error; tests/weather/test_bulk_accuracy.cpp
// checks both against brute-force sums at 550 nm, 1.55 um and 10.6 um.  At
// 1.55 and 10.6 um those sums converge far below the tolerance; at 550 nm the
// resonances of water (k = 2e-9) are narrower than any affordable step, the
// sums agree with each other only to ~1e-5 (beta_pi, p) and ~1e-3 (sigma_abs),
// and the comparison holds only to that; sigma_ext is checked there against
// the contour integral (contour_extinction.hpp), which has no resonances.
//
// Method: Gauss-Kronrod rules from Boost.Math (boost/math/quadrature/
// gauss_kronrod.hpp) in u = ln r, refined adaptively (globally, worst panel
// first, QUADPACK QAG-style) until every component's summed |Kronrod - Gauss|
// plus its resonance bound is below its tolerance times its scale.  One
// efficiency evaluation serves all integrands.
//
// Resonances.  For nearly lossless spheres (Im m < resonance_free_k(),
// src/resonance.hpp) Q(x) carries peaks of half-width down to ~k x / n
// (2e-9 x for water at 550 nm), the morphology-dependent resonances, which no
// sampling finds.  They are located instead: every pole x0 - i gamma of
// a_n, b_n below the real axis in the size range is bracketed and, where it
// matters, located with its residue R (mie/resonances.hpp).  Each pole's
// possible contribution to each integral is bounded by |R|, gamma and the
// size of the rest of the series sampled near x0 (src/resonance_plan.hpp:
// it scales like pi |R| w(x0) times the coefficient's factor, |R| <= the
// pole's radiative half-width).  The poles are taken in the order of that
// bound and each is given a panel of its own on which the integrand times
// |x - x_p|^2 is smooth, integrated by Clenshaw-Curtis with the Lorentzian
// weight 1/|x - x_p|^2 taken exactly (src/pole_rule.hpp, 25 evaluations,
// error from its 13-point subset), until the bounds of the others sum to
// half of each component's allowed error; that sum is reported as the
// resonance error.  Elsewhere no feature is narrower than the rule's
// panels: resonances above the centrifugal barrier (x > n) have
// half-widths >= ~0.05, and panels wider than 2 in x are charged the
// aliasing term below.  A tighter tolerance resolves more poles: the cost
// grows with the accuracy asked (docs/validation/bulk-optics-accuracy.md).
//
// The reported error of each integral is the sum of
//   quadrature  sum over panels of |K - G| (an overestimate for smooth
//               integrands), on resonance panels the difference from the
//               13-point rule plus 4 eps sum |w F| (their weights grow like
//               1/gamma where F is small),
//   tails       q_bound x pi x (exact 2nd moment outside the integration range);
//               the range holds all but tail_fraction of that moment,
//   asymptotic  where x > asymptotic_x, Q_ext is replaced by its large-sphere
//               expansion and |Q_ext - expansion| <= its stated bound is integrated,
//   aliasing    on panels wider than the rule resolves (2 in x for nearly
//               lossless spheres, else 0.6 x points), 1.5 x (sampled range of
//               Q) x (panel's geometric cross-section) is added, since K and G
//               can alias alike there,
//   resonance   the bounds of the resonances not given a panel.
// Panels are split a few at a time and their halves evaluated in parallel
// (TBB, the threads the caller allows); which panels are split does not
// depend on the thread count, so neither does the result.
// If a tolerance cannot be met within max_evaluations, or a moment diverges,
// the function throws std::runtime_error naming the integral and the reason.
// Nearly lossless spheres are the exception: when their resonances would take
// more than the budget (a coarse sea-salt mode at 355 nm has ~1.4e5 poles
// below x = 1,100), the poles with the largest bounds get half the budget,
// the refinement the rest, and the result comes back with the error reached,
// each part as large as it is, and BulkOptics::shortfall saying which
// quantity missed its tolerance by how much.
#pragma once

#include <atomic>
#include <complex>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// Efficiencies of one sphere at size parameter x (what mie::sphere returns).
// qback, moments (chi_0..chi_L) and phase (p at the requested angles, int p
// dOmega = 4 pi) only when the bulk integral asks for them.
struct Efficiency {
  double qext = 0, qsca = 0, qabs = 0, g = 0;
  double qback = 0;
  std::vector<double> moments, phase;
  // alpha1..alpha4, beta1, beta2 for l = 0..L, each L + 1 long, concatenated
  // (legendre_moments.hpp: scattering_matrix_expansion)
  std::vector<double> expansion;
};

// Expansion of the bulk scattering matrix in generalised spherical functions
// (de Rooij & van der Stap 1984; Mishchenko, Travis & Lacis 2002, §4.11;
// legendre_moments.hpp gives the convention): alpha1_l = (2l+1) chi_l.
struct MatrixExpansion {
  std::vector<double> alpha1, alpha2, alpha3, alpha4, beta1, beta2;
};
using EfficiencyFunction = std::function<Efficiency(double x)>;
// Efficiencies of n spheres at once: out[i] at x[i].  The integrals below
// evaluate the nodes of each panel in one call, so a batch that computes
// several spheres per instruction (mie::spheres) pays off.
using EfficiencyBatch = std::function<void(const double* x, std::size_t n, Efficiency* out)>;

// How the bulk integrals are computed, and which quantities they compute.
struct QuadratureSettings {
  double rel_tolerance = 1e-9;     // on sigma_ext, sigma_sca, sigma_abs (relative to sigma_ext)
  // On g, beta_pi, chi_l, p(theta) and the expansion (relative to sigma_sca
  // for g and the expansion, to itself for beta_pi and p(theta), to
  // max(|chi_l|, 1e-3) for chi_l); 0: max(rel_tolerance, 1e-6).  Their integrands carry resonances 10-1000x stronger than Q_ext's
  // (Q_back ~ x |T| per resonance), so each decade costs more there.
  double angular_tolerance = 0;
  int kronrod_points = 31;         // Boost.Math gauss_kronrod order: 15, 21, 31, 41, 51 or 61
  double tail_fraction = 0;        // fraction of the r^2 moment left outside; 0: 1e-3 * rel_tolerance
  std::size_t max_evaluations = 1000000;  // resonance panels (25 each) included
  double asymptotic_x = 0;         // > 0: use the large-x expansion of Q_ext beyond this x (extinction only)
  // Nearly non-absorbing spheres (Im m < resonance_free_k(), see src/resonance.hpp):
  // locate the resonances, resolve those that matter, bound the rest.
  bool estimate_resonances = true;
  // Optional bulk quantities (off by default: the efficiency function must
  // supply them, and the angular ones cost O(N^2) per sphere, N ~ x terms):
  bool backscatter = false;           // beta_pi and the lidar ratio
  int legendre_moments = -1;          // L >= 0: chi_0..chi_L
  std::vector<double> angles_deg;     // bulk phase function at these angles
  bool polarised = false;             // with legendre_moments >= 0: alpha1..4, beta1, 2 of the bulk matrix
  const std::atomic<bool>* cancel = nullptr;  // checked once per panel: Cancelled when set (cancel.hpp)
};

// An integral and the parts of its error bound.
struct IntegralEstimate {
  double value = 0;
  double quadrature_error = 0, tail_error = 0, asymptotic_error = 0, resonance_error = 0;
  double rounding_error = 0;  // contour_extinction.hpp: cancellation of S(0) above the real axis
  double error() const { return quadrature_error + tail_error + asymptotic_error + resonance_error + rounding_error; }
};

// The bulk single-scattering optics of a size distribution, each with its error.
struct BulkOptics {
  IntegralEstimate extinction, scattering, absorption;  // 1/m
  double albedo = 0, albedo_error = 0;
  double asymmetry = 0, asymmetry_error = 0;
  std::size_t evaluations = 0;
  std::size_t resonances_located = 0;   // poles of a_n, b_n located (nearly lossless spheres)
  std::size_t resonances_resolved = 0;  // of those, integrated by a product-rule panel each
  double max_size_parameter = 0;
  bool scattering_computed = true;  // false when the asymptotic region (extinction only) was used
  std::string method;               // rule, tolerance, tail cut, in words
  // Empty when every quantity met its tolerance.  Else (nearly lossless
  // spheres only, see above) which quantity missed it, by what factor, within
  // how many evaluations: the reported errors are then the ones reached.
  std::string shortfall;

  // Filled only when requested (QuadratureSettings) and scattering_computed.
  bool backscatter_computed = false;
  IntegralEstimate backscatter;           // beta_pi, 1/(m sr)
  double lidar_ratio = 0, lidar_ratio_error = 0;  // sigma_ext / beta_pi, sr
  std::vector<double> moments, moments_error;     // chi_0..chi_L (dimensionless, chi_0 = 1)
  std::vector<double> angles_deg, phase, phase_error;  // p(theta), int p dOmega = 4 pi
  MatrixExpansion expansion, expansion_error;          // scattering-weighted, as chi_l
};

// Every field of a result by name, in declaration order, for outputs that
// show them all (the Python bindings): visit(name, value) for a field of its
// own, visit(name, value, error) for a value and its error.  Each
// structured binding names every data member, so a field added to one of
// these structs does not compile until it is listed here, and then reaches
// those outputs without further change.
template <class Visit>
void for_each_field(const IntegralEstimate& e, Visit&& visit) {
  const auto& [value, quadrature_error, tail_error, asymptotic_error, resonance_error, rounding_error] = e;
  visit("value", value);
  visit("quadrature_error", quadrature_error);
  visit("tail_error", tail_error);
  visit("asymptotic_error", asymptotic_error);
  visit("resonance_error", resonance_error);
  visit("rounding_error", rounding_error);
}
// The expansion and its error, coefficient by coefficient: visit(name, values, errors).
template <class Visit>
void for_each_field(const MatrixExpansion& value, const MatrixExpansion& error, Visit&& visit) {
  const auto& [alpha1, alpha2, alpha3, alpha4, beta1, beta2] = value;
  const auto& [alpha1_error, alpha2_error, alpha3_error, alpha4_error, beta1_error, beta2_error] = error;
  visit("alpha1", alpha1, alpha1_error);
  visit("alpha2", alpha2, alpha2_error);
  visit("alpha3", alpha3, alpha3_error);
  visit("alpha4", alpha4, alpha4_error);
  visit("beta1", beta1, beta1_error);
  visit("beta2", beta2, beta2_error);
}
template <class Visit>
void for_each_field(const BulkOptics& b, Visit&& visit) {
  const auto& [extinction, scattering, absorption, albedo, albedo_error, asymmetry, asymmetry_error, evaluations,
               resonances_located, resonances_resolved, max_size_parameter, scattering_computed, method, shortfall,
               backscatter_computed, backscatter,
               lidar_ratio, lidar_ratio_error, moments, moments_error, angles_deg, phase, phase_error, expansion,
               expansion_error] = b;
  visit("extinction", extinction);
  visit("scattering", scattering);
  visit("absorption", absorption);
  visit("albedo", albedo, albedo_error);
  visit("asymmetry", asymmetry, asymmetry_error);
  visit("evaluations", evaluations);
  visit("resonances_located", resonances_located);
  visit("resonances_resolved", resonances_resolved);
  visit("max_size_parameter", max_size_parameter);
  visit("scattering_computed", scattering_computed);
  visit("method", method);
  visit("shortfall", shortfall);
  visit("backscatter_computed", backscatter_computed);
  visit("backscatter", backscatter);
  visit("lidar_ratio", lidar_ratio, lidar_ratio_error);
  visit("moments", moments, moments_error);
  visit("angles_deg", angles_deg);
  visit("phase", phase, phase_error);
  visit("expansion", expansion, expansion_error);
}

// With any efficiency function (analytic test integrands, a cached Mie table...).
// `m` is used only for the error terms (resonances, large-x bound); the default
// (Im m = 1) switches the resonance term off, as for a smooth test integrand.
BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyFunction& q,
                                 const QuadratureSettings& s = {}, std::complex<double> m = {1.33, 1.0});
// The same with a batch efficiency function (same values, fewer calls).
BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyBatch& q,
                                 const QuadratureSettings& s = {}, std::complex<double> m = {1.33, 1.0});

// Lorenz-Mie efficiencies (attenuvis::mie::sphere) of a homogeneous sphere of
// index m, in the working precision the bulk integrals need: all-double
// recurrences (1.45x faster than mie's mixed-precision default at x = 100..1000)
// at x <= 3e4 when |m - 1| >= 0.01.  Calibrated: 3000 random x in [0.01, 3e4]
// (log-uniform) for m = 1.333+1.96e-9i, 1.178+0.0715i, 1.33+0.01i and 1.01 gave
// |Q_ext, Q_sca| differences from the default <= 1.8e-11 relative and |g| <=
// 1e-13, far below any rel_tolerance accepted here; mie.hpp's double-precision
// limits (Q_back, m = 1 + 1e-7) do not enter.  Otherwise mie's default.
EfficiencyFunction mie_efficiencies(std::complex<double> m);
// The same values for a panel of spheres at once (mie::spheres: vector lanes,
// bit for bit mie_efficiencies(m) at each x; Q_back included).
EfficiencyBatch mie_efficiency_batch(std::complex<double> m);
// The same, plus Q_back (always: it is a by-product of the series) and, as
// `s` asks, the Legendre moments chi_0..chi_L (mie::phase_function_moments)
// and the phase function at s.angles_deg (mie::scattering_matrix).
EfficiencyFunction mie_efficiencies(std::complex<double> m, const QuadratureSettings& s);

// With Lorenz-Mie efficiencies of a homogeneous sphere of index m (mie_efficiencies),
// in two passes when moments or a phase function are asked for: the angular
// terms cost O(x^2) per sphere against O(x) for the efficiencies.  Pass A
// integrates sigma, g and beta_pi with cheap evaluations to their
// tolerances; pass B the moments and phase function to the angular
// tolerance (its sigma_sca, their denominator, to the same), locating and
// resolving the resonances for its own components; `evaluations` counts both.
BulkOptics mie_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                           const QuadratureSettings& s = {});

// With Lorenz-Mie efficiencies (attenuvis::mie::sphere, its default precision)
// of a homogeneous sphere of relative refractive index m = n + i k; as
// mie_bulk_optics when angular quantities are asked for.
BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s = {});


}  // namespace attenuvis::weather
