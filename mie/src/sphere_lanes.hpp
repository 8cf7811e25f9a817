// The Mie series of kLanes spheres at once, one sphere per vector lane
// (private to the mie library; used by spheres.cpp).
//
// Every lane performs exactly the operations, in the same order, of the
// double-precision series of series.hpp (Work = Real = double,
// Dₙ(mx) downward) for its own sphere: the same Lentz start at its own table
// length, the same downward, Hankel-ratio and product recurrences, the same
// term formulas (term_block.hpp), the same compensated sums and convergence
// test.  With the library built without contraction (-ffp-contract=off) a lane
// therefore returns bit for bit what sphere() returns; the gain is that the
// serial recurrences, latency-bound in a single call, now advance kLanes
// spheres per instruction.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie::detail {

constexpr int kLanes = 8;

struct LaneProblems {
  double x[kLanes];
  std::complex<double> m[kLanes];
  std::size_t terms[kLanes];  // lane_terms(x, m), as the plan computed it
};

struct LaneResults {
  Efficiencies<double> q[kLanes];
  // false: the lane's series did not converge within its first table
  // (first_terms, detail/term_count.hpp); the caller redoes that sphere with
  // sphere().
  bool converged[kLanes];
};

// Every lane must be one sphere() would evaluate in double with Dₙ(mx) going
// downward and the converged term rule (lane_eligible()).
bool lane_eligible(double x, std::complex<double> m);
// For x and m in the domain: the length of the first table a lane runs
// (first_terms, detail/term_count.hpp), the order count a group is sized by;
// 0 where the sphere is not lane-eligible.
std::size_t lane_terms(double x, std::complex<double> m);
// One or two groups (`groups` entries of in and out; two run their downward
// passes interleaved).  kernel: an index into lane_instruction_sets() (0: the
// best for this CPU).
constexpr int kMaxGroups = 2;
void sphere_lanes(const LaneProblems* in, LaneResults* out, int groups = 1, int kernel = 0);

// The instruction sets of the lane kernels this CPU can run, best first:
// "avx512" (x86-64-v4), "avx2" (x86-64-v3), "generic" (any CPU).  All give
// the same bits.
std::vector<std::string> lane_instruction_sets();
// The index of a name in lane_instruction_sets(); "" gives 0; -1 if absent.
int lane_kernel_index(const std::string& name);

}  // namespace attenuvis::mie::detail
