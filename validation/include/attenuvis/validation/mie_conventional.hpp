// A plain textbook Lorenz–Mie evaluation, kept as the "conventional code"
// baseline of the error-against-run-time benchmark.
//
// It follows Bohren & Huffman (1983), chapter 4 and the BHMIE program of their
// Appendix A, with the two choices most widely used codes make: Wiscombe's
// term count N = x + 4.05 x^(1/3) + 2 (NCAR/TN-140, eq. R50 for 8 < x < 4200,
// used here at every x) and the logarithmic derivative D_n(mx) by downward
// recurrence (B&H eq. 4.89) started from zero at max(N, |mx|) + 15.  It has no
// Lentz continued fraction, no series for small x and no convergence test: it
// exists to show numerically what those omissions cost (the Mie traps
// truncation, start-value and small-x of mie/src/series.hpp).
// It is NOT Wiscombe's MIEV0; do not label its timings as MIEV0's.
#pragma once

#include <complex>

namespace attenuvis::validation {

/// Efficiencies from the conventional code; conventions as attenuvis::mie
/// (m = n + i k with k >= 0, Qback = 4|S1(pi)|^2 / x^2, the Bohren–Huffman one).
struct ConventionalMieResult {
  double qext = 0, qsca = 0, qabs = 0, qback = 0, g = 0;
  int terms = 0;  ///< Wiscombe's N actually summed
};

/// Wiscombe's term count, N = floor(x + 4.05 x^(1/3) + 2).
int wiscombe_term_count(double x);

/// Bohren–Huffman style evaluation in double precision (see file comment).
/// Storage is O(N) complex values; no checks beyond x > 0.
ConventionalMieResult conventional_bhmie(double x, std::complex<double> m);

}  // namespace attenuvis::validation
