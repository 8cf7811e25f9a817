// The Mie series of kLanes spheres at once, one sphere per vector lane
// (private to the mie library; used by spheres.cpp).
//
// Every lane performs exactly the operations, in the same order, of the
// double-precision series of attenuvis/mie/series.hpp (Work = Real = double,
// Dₙ(mx) downward) for its own sphere: the same Lentz start at its own table
// length, the same downward, Hankel-ratio and product recurrences, the same
// term formulas (term_block.hpp), the same compensated sums and convergence
// test.  With the library built without contraction (-ffp-contract=off) a lane
// therefore returns bit for bit what sphere() returns; the gain is that the
// serial recurrences, latency-bound in a single call, now advance kLanes
// spheres per instruction.
#pragma once

#include <complex>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie::detail {

constexpr int kLanes = 8;

struct LaneProblems {
  double x[kLanes];
  std::complex<double> m[kLanes];
};

struct LaneResults {
  Efficiencies<double> q[kLanes];
  // false: the lane's series did not converge within its first table
  // (first_terms in series.hpp); the caller redoes that sphere with sphere().
  bool converged[kLanes];
};

// Every lane must be one sphere() would evaluate in double with Dₙ(mx) going
// downward and the converged term rule (lane_eligible()).
bool lane_eligible(double x, std::complex<double> m);
void sphere_lanes(const LaneProblems& in, LaneResults& out);

}  // namespace attenuvis::mie::detail
