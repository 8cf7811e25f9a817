// C entry point into an older attenuvis Mie core, compiled by
// build_mie_baseline.sh into a shared library that mie_error_vs_time loads
// with dlopen (--baseline).  Everything but this function is hidden
// (-fvisibility=hidden), so the old core's C++ symbols never meet the current
// ones.  Not part of the CMake build: it is compiled against the old sources.
#include <complex>
#include <exception>

#include "attenuvis/mie.hpp"

// q[0..5] = Qext, Qsca, Qabs, Qback, g, terms.  Returns 0, or 1 if the core threw.
extern "C" __attribute__((visibility("default"))) int attenuvis_mie_baseline_sphere(double x, double m_re,
                                                                                    double m_im, double* q) {
  try {
    const auto e = attenuvis::mie::sphere(x, std::complex<double>(m_re, m_im));
    q[0] = e.qext, q[1] = e.qsca, q[2] = e.qabs, q[3] = e.qback, q[4] = e.g, q[5] = double(e.terms);
    return 0;
  } catch (const std::exception&) {
    return 1;
  }
}
