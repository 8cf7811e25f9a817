// The current core's spheres() over one batch of size parameters, on one
// thread and on several: the two batch calls that both comparisons of the
// core with another code time (mie_baseline.cpp, mie_miev0.cpp).  Defined in
// mie_baseline.cpp beside batch_size_parameters(), the batch both use.
#pragma once

#include <complex>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::validation {

// The threads of a many-spheres timing: `requested`, or every hardware thread
// for 0.
unsigned batch_threads(unsigned requested);

class CoreBatch {
 public:
  // `x` must outlive the object.
  CoreBatch(const std::vector<double>& x, std::complex<double> m, unsigned threads);

  // spheres() over the batch on one thread, and on `threads` threads; each
  // returns the first sphere's Qext, so that the call is not optimised away.
  double one_thread() { return run(1); }
  double all_threads() { return run(threads_); }
  // The efficiencies of the last call, one per size parameter.
  const std::vector<mie::Efficiencies<double>>& results() const { return out_; }

 private:
  double run(unsigned threads);

  const std::vector<double>& x_;
  std::complex<double> m_;
  unsigned threads_;
  std::vector<mie::Efficiencies<double>> out_;
};

}  // namespace attenuvis::validation
