// Argument checks and the automatic choice of working precision of the
// layered-sphere entry points, shared by layered_sphere()/layered_scatter()
// (layered_double.cpp) and the batch layered_spheres() (layered_spheres.cpp).
// Private to the mie library.
#pragma once

#include <complex>
#include <cstddef>
#include <sstream>
#include <string>

#include "attenuvis/mie.hpp"
#include "sphere_checks.hpp"

namespace attenuvis::mie::detail {

// The domain of attenuvis/mie/layered.hpp.
constexpr std::size_t kMaxLayers = 1000;
constexpr double kMaxLayeredX = 2e5;
// |m x| bound of every layer: the Lentz start of yₙ(m x) runs ~|m x| steps,
// and k/z stays exact for k < 2^26 (ScaledInverse, log_derivative.hpp).
constexpr double kMaxLayeredMx = 1e7;

// Whether a layered sphere is in the domain, by comparisons only (the common
// case: no message built, no hypot).  Conservative near |m| = 0.5 like
// index_in_domain(); layered_error() decides exactly.  NaN fails every test.
inline bool layered_in_domain(const double* x, const std::complex<double>* m, std::size_t layers,
                              std::size_t first_index) {
  if (layers < 1 || layers > kMaxLayers || !(x[layers - 1] <= kMaxLayeredX)) return false;
  for (std::size_t l = 0; l < layers; ++l) {
    if (!(x[l] >= kMinX && x[l] <= kMaxX) || (l > 0 && !(x[l] >= x[l - 1]))) return false;
    if (l < first_index) continue;
    const std::complex<double> ml = m[l - first_index];
    if (!index_in_domain(ml)) return false;
    const double mx2 = (ml.real() * ml.real() + ml.imag() * ml.imag()) * x[l] * x[l];
    if (!(mx2 <= 0.999999 * kMaxLayeredMx * kMaxLayeredMx)) return false;
  }
  return true;
}

// "" for a valid layered sphere, else the message (naming the layer).
// x: `layers` size parameters; m: the indices of layers first_index ..
// layers − 1 (first_index = 1 on a perfectly conducting core, whose index is
// not given), m[l − first_index] for layer l.
inline std::string layered_error(const double* x, const std::complex<double>* m, std::size_t layers,
                                 std::size_t first_index) {
  if (layered_in_domain(x, m, layers, first_index)) return {};
  std::ostringstream os;
  os.precision(17);
  if (layers < 1 || layers > kMaxLayers) {
    os << "mie: a layered sphere needs 1 to " << kMaxLayers << " layers, got " << layers;
    return os.str();
  }
  for (std::size_t l = 0; l < layers; ++l) {
    const std::string e = size_parameter_error(x[l]);
    if (!e.empty()) return "mie: layer " + std::to_string(l) + ": " + e.substr(5);
    if (l > 0 && !(x[l] >= x[l - 1])) {
      os << "mie: layer " << l << ": size parameters must not decrease from the core out, got x = " << x[l]
         << " after " << x[l - 1];
      return os.str();
    }
    if (l >= first_index) {
      const std::complex<double> ml = m[l - first_index];
      const std::string em = refractive_index_error(ml);
      if (!em.empty()) return "mie: layer " + std::to_string(l) + ": " + em.substr(5);
      if (std::abs(ml) * x[l] > kMaxLayeredMx) {
        os << "mie: layer " << l << ": |m| x = " << std::abs(ml) * x[l] << " exceeds " << kMaxLayeredMx
           << " (the recurrences would need that many steps)";
        return os.str();
      }
    }
  }
  if (x[layers - 1] > kMaxLayeredX) {
    os << "mie: layered sphere: outer size parameter x = " << x[layers - 1] << " exceeds " << kMaxLayeredX;
    return os.str();
  }
  return {};
}

// Where the recurrences need extended precision (Options::precision unset),
// measured against the 50-digit referee (tests/mie/test_layered_referee.cpp):
//  * above kLayeredDoubleUpTo (as for the homogeneous sphere): rounding of
//    the recurrences accumulates over ~x orders and Qback's alternating sum
//    amplifies it (trap back-cancellation);
//  * every layer within kLayeredNearOne of the medium: the particle barely
//    scatters, the numerators of aₙ, bₙ are O(m − 1) and the layered series
//    forms them by difference (trap m-near-1), so double loses ~ε/|m − 1|,
//    more at a zero of ψₙ(x) (trap psi-zero): measured with all layers at
//    1 + 1e-6, 2.7e-10 in Qext and 4.4e-10 in Qback at x = 41.9 (a zero of
//    ψ₃₅), 2.3e-10 in Qback at 1 + 1e-5; in long double 2000 times less.
constexpr double kLayeredDoubleUpTo = 1e4;
constexpr double kLayeredNearOne = 1e-3;

inline bool layered_use_extended(const double* x, const std::complex<double>* m, std::size_t layers,
                                 std::size_t first_index, const Options& options) {
  if (options.precision) return *options.precision == Precision::extended;
  const double outer = x[layers - 1];
  if (outer <= options.extended_above) return false;
  if (outer > kLayeredDoubleUpTo) return true;
  if (first_index > 0) return false;  // a conducting core scatters strongly
  for (std::size_t l = 0; l < layers; ++l)
    if (std::norm(m[l] - 1.0) >= kLayeredNearOne * kLayeredNearOne) return false;
  return true;
}

// The layered sphere (x, m) of `layers` layers, already checked against the
// domain (layered_error() empty): leaves out layers of zero thickness, hands
// one layer to the homogeneous sphere and runs the series in the precision
// of layered_use_extended() (layered_double.cpp).
Scattering<double> layered_evaluate(const double* x, const std::complex<double>* m, std::size_t layers,
                                    bool conducting_core, const Extras& extras, const Options& options);

}  // namespace attenuvis::mie::detail
