// Efficiencies of many spheres in one call (size distributions, tables,
// Monte Carlo): the same values as sphere() one by one, faster.
//
// How: the spheres that sphere() evaluates in double with Dₙ(mx) going
// downward (the default precision rule, attenuvis/mie.hpp, up to x = 1e4)
// are ordered by their number of terms and evaluated kLanes = 8 at a time,
// one sphere per vector lane: the serial recurrences that bound a single call
// by their latency then advance eight spheres per instruction (AVX-512, AVX2
// or the baseline SSE2, chosen at run time).  Each lane performs the very
// operations of sphere(), so its results are bit for bit those of sphere()
// (the library is built without fused multiply-add contraction).  Every other sphere (extended precision, upward
// Dₙ(mx), a term rule or precision other than the default) goes through
// sphere() itself.  The work is split
// over threads.
//
// Bad input never throws: each bad element is reported with its index and the
// reason, its output is left as NaN, and every good element is computed.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie {

// How spheres() evaluates: the options of sphere() and the threads to use.
struct SpheresOptions {
  Options options;       // term rule and precision, as for sphere()
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency(); 1: the calling thread only
  // Vector kernels: "" the best this CPU runs, else one of
  // spheres_instruction_sets() (benchmarks and tests; every one gives the
  // same bits).  A name this CPU cannot run throws std::invalid_argument.
  std::string instruction_set;
};

// The instruction sets of the vector path this CPU can run, best first:
// "avx512" (x86-64-v4), "avx2" (x86-64-v3), "generic" (any CPU).
std::vector<std::string> spheres_instruction_sets();

// A sphere spheres() could not evaluate, and why.
struct SphereError {
  std::size_t index;    // position in the input arrays
  std::string message;  // what is wrong with it (as sphere() would throw)
};

// out[i] = sphere(x[i], m[i]) for i < count.  Returns the bad elements, in
// index order (empty when all are good).
std::vector<SphereError> spheres(const double* x, const std::complex<double>* m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options = {});
// out[i] = sphere(x[i], m) for i < count.
std::vector<SphereError> spheres(const double* x, std::complex<double> m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options = {});

}  // namespace attenuvis::mie
