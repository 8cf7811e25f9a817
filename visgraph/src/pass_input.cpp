// The checks every visibility pass runs on its input (pass_input.hpp).
#include "pass_input.hpp"

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph::detail {

namespace {

void validate(const VisibilityOptions& o) {
  for (double s : o.sigmas)
    if (!std::isfinite(s) || s < 0) throw std::invalid_argument("visibility: sigma must be finite and >= 0 (1/m)");
  if (!(o.prune_below >= 0) || !(o.prune_below < 1)) throw std::invalid_argument("visibility: prune_below (the pruning tolerance eps) must be in [0, 1)");
  if (!(o.max_distance > 0)) throw std::invalid_argument("visibility: max distance must be positive");
  if (o.threads < 0) throw std::invalid_argument("visibility: thread count must be >= 0");
  if (o.share.count < 1 || o.share.index < 0 || o.share.index >= o.share.count)
    throw std::invalid_argument("visibility: share " + std::to_string(o.share.index) + " of " +
                                std::to_string(o.share.count) + " does not exist");
  if (o.share.count > 1 && !o.share.combine)
    throw std::invalid_argument("visibility: a pass in several shares needs a combine step");
}

// The fixed-point sums cannot overflow.  Every contribution is
// non-negative, so each per-thread partial sum and their total are bounded by
// the sum of all contributions a node receives: at most P partners (N - 1
// all-to-all, M to targets), each adding
//   C   <= 2^40                 (C <= 1 in units of 2^-40),
//   d   <= D 2^20 + 1/2         (D: the largest distance a pair can have, m),
//   1 to the degree and to the within-radius count.
// So P 2^40 < 2^63 needs P < 2^23, and P (D 2^20 + 1) < 2^63 bounds the
// distance sums.  Inside the coordinate range (limits.hpp) D <= sqrt(3) 2e7 m
// < 2^26 m, so any run of fewer than 2^17 = 131,072 partners per node is safe
// whatever its geometry (the default work cap, 2e9 pairs, allows at most
// ~63,000 all-to-all nodes); a larger run is checked here with the actual D
// (the diagonal of the points' bounding box, or max_distance when smaller)
// and refused, never wrapped.  contrast_lanes also needs d < 2^32 m, which the
// coordinate range guarantees.
void check_fixed_point_range(const Points& S, const Points& P, bool symmetric, double max_distance) {
  const double partners = symmetric ? static_cast<double>(S.size()) - 1 : static_cast<double>(P.size());
  if (partners >= 8388608.0)  // 2^23
    throw std::invalid_argument("visibility: " + std::to_string(static_cast<long long>(partners)) +
                                " partners per node, more than the 2^23 = 8,388,608 the 64-bit contrast sums hold");
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (const Points* p : {&S, &P})
    for (std::size_t i = 0; i < p->size(); ++i) {
      const double v[3] = {p->x[i], p->y[i], p->z[i]};
      for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
    }
  const double diagonal = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double d_max = std::min(diagonal, max_distance);
  if (partners * (d_max * kDistanceScale + 1) >= 9.2e18)  // < 2^63 = 9.223e18
    throw std::invalid_argument("visibility: " + std::to_string(static_cast<long long>(partners)) +
                                " partners per node up to " + std::to_string(static_cast<long long>(d_max)) +
                                " m apart overflow the 64-bit distance sums: limit the distance (max distance) "
                                "or use fewer nodes");
}

}  // namespace

void check_pass_input(const Points& sources, const Points& partners, bool symmetric, const VisibilityOptions& options) {
  validate(options);
  if (sources.size() == 0) throw std::invalid_argument("visibility: no nodes");
  if (!symmetric && partners.size() == 0) throw std::invalid_argument("visibility: no targets");
  if (sources.size() > 0xFFFFFFFFu || partners.size() > 0xFFFFFFFFu)
    throw std::invalid_argument("visibility: more than 2^32 nodes");
  check_fixed_point_range(sources, partners, symmetric, options.max_distance);
}

}  // namespace attenuvis::visgraph::detail
