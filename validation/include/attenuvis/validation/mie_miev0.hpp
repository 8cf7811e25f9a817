// The Mie core against W. J. Wiscombe's MIEV0 (NCAR Technical Note
// TN-140+STR, 1979, revised 1996), for users who have its Fortran source.
// MIEV0 is not part of attenuvis: validation/bench/miev0/build_miev0.sh
// compiles the user's copy (gfortran -O2, default REAL and COMPLEX promoted to
// double) into a shared library, and Miev0Library loads it with dlopen
// (symbol miev0_).  Timing as in mie_baseline.hpp: alternating blocks, thread
// CPU time, minimum over blocks, all in the same run.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/validation/mie_accuracy.hpp"
#include "attenuvis/validation/mie_baseline.hpp"
#include "attenuvis/validation/shared_library.hpp"

namespace attenuvis::validation {

// Wiscombe's MIEV0, compiled by the user into a shared library
// (validation/bench/miev0/build_miev0.sh) and loaded to be timed.
class Miev0Library {
 public:
  /// Loads the library; throws std::runtime_error naming the path and the
  /// loader's message if it cannot be loaded or has no miev0_.
  explicit Miev0Library(const std::string& library_path);

  /// MIEV0 with no angles and no moments (the efficiencies, g and the
  /// backscatter amplitude, from which Qback = 4|S(π)|²/x²).
  MieQuantities sphere(double x, std::complex<double> m) const;
  const std::string& path() const { return library_.path(); }

 private:
  SharedLibrary library_;
};

/// One (x, m): ns per call of MIEV0, of attenuvis's default sphere() and of
/// sphere() with Wiscombe's term count (the fast mode closest to MIEV0's own
/// truncation), and each one's error against the 50-digit referee.
struct Miev0Cell {
  double x = 0;
  std::complex<double> m;
  double ns_miev0 = 0, ns_default = 0, ns_wiscombe = 0;
  double err_miev0 = -1, err_default = -1, err_wiscombe = -1;  ///< -1: not measured (x above max_referee_x)
  int terms_default = 0, terms_wiscombe = 0;
  /// attenuvis default time / MIEV0 time (below 1: attenuvis is faster).
  double ratio() const { return ns_default / ns_miev0; }
};
// Times sphere() against MIEV0 on every cell of `options`, and the table of it.
std::vector<Miev0Cell> mie_speed_vs_miev0(const Miev0Library& miev0, const SpeedOptions& options = {});
std::string format_speed_vs_miev0(const std::vector<Miev0Cell>& cells);

/// Many spheres (as BatchSpeed, the same size parameters): MIEV0 in a loop
/// against sphere() in a loop and spheres() on one and on all threads.
struct Miev0Batch {
  double x_min = 0.01, x_max = 100;
  std::complex<double> m{1.33, 1e-8};
  std::size_t count = 20000;
  unsigned threads = 0;  ///< 0 = hardware_concurrency() (set on return)
  double ns_miev0 = 0, ns_single = 0, ns_batch = 0, ns_batch_threads = 0;
};
Miev0Batch mie_batch_vs_miev0(const Miev0Library& miev0, Miev0Batch setup, int blocks = 5);
std::string format_batch_vs_miev0(const Miev0Batch& b);

}  // namespace attenuvis::validation
