// Many spheres in one call: see attenuvis/mie/spheres.hpp.
#include "attenuvis/mie/spheres.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "shared_items.hpp"
#include "sphere_checks.hpp"
#include "sphere_lanes.hpp"

namespace attenuvis::mie {
namespace {

using detail::kLanes;

Efficiencies<double> not_a_number() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Efficiencies<double> q;
  q.qext = q.qsca = q.qabs = q.qback = q.qpr = q.g = nan;
  return q;
}

using detail::lane_options;

// The work: groups of kLanes lane-eligible spheres, ordered by table length
// (so that a group's lanes run nearly the same number of orders), then the
// remaining spheres one by one.
struct Plan {
  std::vector<std::size_t> lanes;   // indices, by table length, padded to a multiple of kLanes
  std::vector<std::uint32_t> terms; // table length of each entry of `lanes` (lane_terms)
  std::size_t lane_count = 0;       // real entries in `lanes`
  std::vector<std::size_t> single;  // indices for sphere()
  int kernel = 0;                   // lane kernels (sphere_lanes.hpp)
};

// Orders `lanes` by `terms` (counting sort: stable, so ties keep input
// order and the plan is deterministic).
void order_by_terms(std::vector<std::size_t>& lanes, std::vector<std::uint32_t>& terms) {
  if (lanes.size() <= static_cast<std::size_t>(kLanes)) return;
  const std::uint32_t top = *std::max_element(terms.begin(), terms.end());
  std::vector<std::size_t> start(static_cast<std::size_t>(top) + 2, 0);
  for (std::uint32_t t : terms) ++start[t + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::size_t> sorted(lanes.size());
  std::vector<std::uint32_t> sorted_terms(lanes.size());
  for (std::size_t k = 0; k < lanes.size(); ++k) {
    const std::size_t to = start[terms[k]]++;
    sorted[to] = lanes[k];
    sorted_terms[to] = terms[k];
  }
  lanes.swap(sorted);
  terms.swap(sorted_terms);
}

// Groups first .. first + count − 1 (count <= detail::kMaxGroups) in one call.
template <class IndexOf>
void evaluate_groups(const Plan& plan, std::size_t first, int count, const double* x, const IndexOf& m_of,
                     const Options& options, Efficiencies<double>* out) {
  detail::LaneProblems in[detail::kMaxGroups];
  detail::LaneResults res[detail::kMaxGroups];
  for (int g = 0; g < count; ++g)
    for (int j = 0; j < kLanes; ++j) {
      const std::size_t slot = (first + g) * kLanes + j;
      const std::size_t i = plan.lanes[slot];
      in[g].x[j] = x[i];
      in[g].m[j] = m_of(i);
      in[g].terms[j] = plan.terms[slot];
    }
  detail::sphere_lanes(in, res, count, plan.kernel);
  for (int g = 0; g < count; ++g)
    for (int j = 0; j < kLanes; ++j) {
      const std::size_t slot = (first + g) * kLanes + j;
      if (slot >= plan.lane_count) break;  // padding repeats the last sphere
      const std::size_t i = plan.lanes[slot];
      // A lane whose first table was too short: sphere() redoes it with the longer one.
      out[i] = res[g].converged[j] ? res[g].q[j] : sphere(x[i], m_of(i), options);
    }
}

template <class IndexOf>
std::vector<SphereError> run(const double* x, const IndexOf& m_of, std::size_t count, Efficiencies<double>* out,
                             const SpheresOptions& options) {
  std::vector<SphereError> errors;
  Plan plan;
  plan.kernel = detail::lane_kernel_index(options.instruction_set);
  if (plan.kernel < 0)
    throw std::invalid_argument("mie: spheres(): instruction set '" + options.instruction_set +
                                "' is not available on this CPU");
  const bool lanes_allowed = lane_options(options.options);
  std::vector<std::uint32_t>& terms = plan.terms;
  for (std::size_t i = 0; i < count; ++i) {
    const std::complex<double> m = m_of(i);
    // The common case, tested without building a message (NaN fails the comparisons).
    if (!(x[i] >= detail::kMinX && x[i] <= detail::kMaxX && detail::index_in_domain(m))) {
      std::string e = detail::size_parameter_error(x[i]);
      if (e.empty()) e = detail::refractive_index_error(m);
      if (!e.empty()) {
        errors.push_back({i, e});
        out[i] = not_a_number();
        continue;
      }
    }
    const std::size_t n = lanes_allowed ? detail::lane_terms(x[i], m) : 0;
    if (n > 0) {
      plan.lanes.push_back(i);
      terms.push_back(static_cast<std::uint32_t>(n));
    } else {
      plan.single.push_back(i);
    }
  }
  order_by_terms(plan.lanes, terms);
  plan.lane_count = plan.lanes.size();
  while (plan.lanes.size() % kLanes != 0) {
    plan.lanes.push_back(plan.lanes.back());
    plan.terms.push_back(plan.terms.back());
  }
  const std::size_t groups = plan.lanes.size() / kLanes;
  // Lane work items: pairs of neighbouring groups (similar table lengths),
  // whose downward passes run interleaved; the last may be a single group.
  const std::size_t pairs = (groups + 1) / 2;
  // Work items: the single spheres (extended precision or long series: the
  // costliest), then the lane groups from the longest tables down; threads
  // take the next item from a shared counter (items differ in cost by orders
  // of magnitude, and the cheap ones last keep the threads' finishing times
  // close).
  const std::size_t singles = plan.single.size();
  const std::size_t items = pairs + singles;
  detail::share_items(items, options.threads, [&](std::size_t k) {
    if (k >= singles) {
      const std::size_t pair = pairs - 1 - (k - singles);
      evaluate_groups(plan, 2 * pair, 2 * pair + 1 < groups ? 2 : 1, x, m_of, options.options, out);
    } else {
      const std::size_t i = plan.single[k];
      out[i] = sphere(x[i], m_of(i), options.options);
    }
  });
  return errors;
}

}  // namespace

std::vector<std::string> spheres_instruction_sets() { return detail::lane_instruction_sets(); }

std::vector<SphereError> spheres(const double* x, const std::complex<double>* m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options) {
  return run(x, [m](std::size_t i) { return m[i]; }, count, out, options);
}

std::vector<SphereError> spheres(const double* x, std::complex<double> m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options) {
  return run(x, [m](std::size_t) { return m; }, count, out, options);
}

}  // namespace attenuvis::mie
