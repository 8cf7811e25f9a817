// The 50-digit referee: the same Mie series (mie/src/series.hpp) run in
// Boost.Multiprecision cpp_bin_float_50 / cpp_complex_50.  Used by tests and
// benchmarks to measure the error of the double-precision product; it is
// compiled in its own translation unit (mie/src/sphere_referee.cpp) because
// multiprecision templates compile slowly.  About 1–3 µs per series term.
//
// A double input is converted exactly, so sphere_referee(x, m) is the
// 50-digit value of the very problem sphere(x, m) solves.
#pragma once

#include <complex>
#include <string>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/cpp_complex.hpp>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie {

// The referee's real type: 50 decimal digits (Boost.Multiprecision).
using Referee = boost::multiprecision::cpp_bin_float_50;

// Its complex type: 50-digit complex numbers.
template <>
struct ComplexOf<Referee> {
  using type = boost::multiprecision::cpp_complex_50;
};

// scatter() at 50 digits: the same equations and recurrences as the double
// core, the reference every accuracy test compares with.
Scattering<Referee> scatter_referee(const Referee& x, const Complex<Referee>& m, const Extras& extras = {},
                                    const Options& options = {});
Scattering<Referee> scatter_referee(const Referee& x, PerfectConductor, const Extras& extras = {},
                                    const Options& options = {});

// Exact conversion of double input.
Efficiencies<Referee> sphere_referee(double x, std::complex<double> m, const Options& options = {});
// Decimal strings, e.g. sphere_referee("1e4", "1.33", "1e-5"): the referee of
// the decimal problem itself, not of its nearest double.
Efficiencies<Referee> sphere_referee(const std::string& x, const std::string& m_re, const std::string& m_im,
                                     const Options& options = {});

}  // namespace attenuvis::mie
