// Many spheres in one call: see attenuvis/mie/spheres.hpp.
#include "attenuvis/mie/spheres.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <numeric>
#include <thread>

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

using detail::default_options;

// The work: groups of kLanes lane-eligible spheres (sorted by x, so that a
// group's table lengths are close), then the remaining spheres one by one.
struct Plan {
  std::vector<std::size_t> lanes;   // indices, sorted by x, padded to a multiple of kLanes
  std::size_t lane_count = 0;       // real entries in `lanes`
  std::vector<std::size_t> single;  // indices for sphere()
};

template <class IndexOf>
void evaluate_group(const Plan& plan, std::size_t g, const double* x, const IndexOf& m_of, Efficiencies<double>* out) {
  detail::LaneProblems in;
  detail::LaneResults res;
  for (int j = 0; j < kLanes; ++j) {
    const std::size_t i = plan.lanes[g * kLanes + j];
    in.x[j] = x[i];
    in.m[j] = m_of(i);
  }
  detail::sphere_lanes(in, res);
  for (int j = 0; j < kLanes; ++j) {
    const std::size_t slot = g * kLanes + j;
    if (slot >= plan.lane_count) break;  // padding repeats the last sphere
    const std::size_t i = plan.lanes[slot];
    // A lane whose first table was too short: sphere() redoes it with the longer one.
    out[i] = res.converged[j] ? res.q[j] : sphere(x[i], m_of(i));
  }
}

template <class IndexOf>
std::vector<SphereError> run(const double* x, const IndexOf& m_of, std::size_t count, Efficiencies<double>* out,
                             const SpheresOptions& options) {
  std::vector<SphereError> errors;
  Plan plan;
  const bool lanes_allowed = default_options(options.options);
  for (std::size_t i = 0; i < count; ++i) {
    std::string e = detail::size_parameter_error(x[i]);
    if (e.empty()) e = detail::refractive_index_error(m_of(i));
    if (!e.empty()) {
      errors.push_back({i, e});
      out[i] = not_a_number();
    } else if (lanes_allowed && detail::lane_eligible(x[i], m_of(i))) {
      plan.lanes.push_back(i);
    } else {
      plan.single.push_back(i);
    }
  }
  std::sort(plan.lanes.begin(), plan.lanes.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  plan.lane_count = plan.lanes.size();
  while (plan.lanes.size() % kLanes != 0) plan.lanes.push_back(plan.lanes.back());
  const std::size_t groups = plan.lanes.size() / kLanes;
  // Work items: the lane groups, then the single spheres; threads take the
  // next item from a shared counter (items differ in cost by orders of magnitude).
  const std::size_t items = groups + plan.single.size();
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(1, items / 4)));
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto worker = [&] {
    try {
      for (std::size_t k; (k = next.fetch_add(1)) < items;) {
        if (k < groups) {
          evaluate_group(plan, k, x, m_of, out);
        } else {
          const std::size_t i = plan.single[k - groups];
          out[i] = sphere(x[i], m_of(i), options.options);
        }
      }
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return errors;
}

}  // namespace

std::vector<SphereError> spheres(const double* x, const std::complex<double>* m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options) {
  return run(x, [m](std::size_t i) { return m[i]; }, count, out, options);
}

std::vector<SphereError> spheres(const double* x, std::complex<double> m, std::size_t count,
                                 Efficiencies<double>* out, const SpheresOptions& options) {
  return run(x, [m](std::size_t) { return m; }, count, out, options);
}

}  // namespace attenuvis::mie
