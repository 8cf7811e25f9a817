// Which resonances the size integral resolves: see resonance_plan.hpp.
#include "resonance_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <boost/math/constants/constants.hpp>

#include <tbb/parallel_for.h>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/cancel.hpp"

namespace attenuvis::weather::detail {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// The largest share of its allowed error that `bound` takes in any component.
double worst_share(const Vec& bound, const Vec& allowed) {
  double worst = 0;
  for (std::size_t c = 0; c < bound.size(); ++c)
    if (allowed[c] > 0) worst = std::max(worst, bound[c] / allowed[c]);
  return worst;
}

bool within(const Vec& total, const Vec& allowed, double fraction) {
  for (std::size_t c = 0; c < total.size(); ++c)
    if (allowed[c] > 0 && total[c] > fraction * allowed[c]) return false;
  return true;
}

void add(Vec& total, const Vec& v, double sign = 1) {
  for (std::size_t c = 0; c < total.size(); ++c) total[c] += sign * v[c];
}

// Half-width from which the Gauss-Kronrod panels (no wider than 2 in x where
// resonances are, 31 nodes: spacing <= 0.1) sample a peak with two nodes or
// more, so that |K - G| sees it: such a pole needs neither a panel nor a bound.
constexpr double kSampledHalfWidth = 0.1;

// Narrowest half-width a rule can resolve at x: the pole is located to about
// n eps x and the sampled values near it carry eps x / gamma relative errors.
double narrowest_resolvable(double x) { return 1e5 * std::numeric_limits<double>::epsilon() * std::max(x, 1.0); }

struct Candidate {
  mie::ResonanceBracket bracket;
  Vec estimate;  // bound from the width estimate
  double share = 0;
  bool located = false;
  mie::Resonance pole;
  Vec bound;  // from the located pole
};

// How far the rule of a resolved pole reaches on either side: a quarter in
// x at most, 0.4 of the way to the nearest other resolved pole (whose peak
// then lies well outside its panel), never across a breakpoint of the
// density.  The rule is exact for the pole however its reach compares with
// the half-width: a broad peak's tails beyond the reach are smooth there.
double reach_of(double x0, double left_neighbour, double right_neighbour, const std::vector<double>& breakpoints_x) {
  double reach = 0.25;
  reach = std::min(reach, 0.4 * (x0 - left_neighbour));
  reach = std::min(reach, 0.4 * (right_neighbour - x0));
  for (double b : breakpoints_x) reach = std::min(reach, std::abs(b - x0));
  return reach;
}

std::string too_costly(std::size_t needed, std::size_t max_resolved) {
  return "resolving the resonances of the nearly lossless particles to the tolerance needs " +
         std::to_string(needed) + " resonance panels of 25 evaluations, beyond the budget's " +
         std::to_string(max_resolved) + ": the others are bounded, not resolved";
}

}  // namespace

Vec resonance_bound(const Layout& layout, int order, double x0, double residue, double half_width,
                    const NearbySamples& near) {
  Vec b(static_cast<std::size_t>(layout.size()), 0.0);
  const double N = 2.0 * order + 1, x2 = x0 * x0;
  const double peak = residue / half_width;  // |R| / gamma
  const double i1 = 2 * kPi * residue * near.weight_x;
  const double i2 = 2 * kPi * residue * peak * near.weight_x;
  b[kExt] = 2 * N / x2 * i1;
  b[kSca] = 2 * N / x2 * (i2 + 2 * (1 + peak) * i1);
  b[kAbs] = b[kExt] + b[kSca];
  const double q_sca = near.q_max[kSca] + 2 * N / x2 * peak * peak;
  const double cauchy_schwarz = (2 * N * i2 + 2 * std::sqrt(2 * N) * x0 * std::sqrt(q_sca) * i1) / x2;
  b[kGSca] = cauchy_schwarz;
  if (layout.back) {
    const double t_max = x0 * std::sqrt(4 * kPi * near.q_max[kBack]) + N * peak;
    b[kBack] = (N * N * i2 + 2 * N * t_max * i1) / (4 * kPi * x2);
  }
  for (int l = 0; l < layout.moments; ++l) b[layout.moment(l)] = cauchy_schwarz;
  for (int j = 0; j < layout.angles; ++j) {
    const double s_max = x0 * std::sqrt(near.q_max[layout.angle(j)]) + N * peak;
    b[layout.angle(j)] = 2 / x2 * (N * N * i2 / 2 + N * s_max * i1);
  }
  for (int i = 0; i < layout.expansion; ++i) {
    const int l = i % std::max(layout.moments, 1);
    b[layout.expansion_at(i)] = 2 * (2 * l + 1) * cauchy_schwarz;
  }
  return b;
}

ResonancePlan plan_resonances(std::complex<double> m, double x_lo, double x_hi, const Layout& layout,
                              const Vec& allowed, const std::vector<double>& breakpoints_x,
                              const std::function<NearbySamples(double)>& near, std::size_t max_resolved,
                              const std::atomic<bool>* cancel) {
  ResonancePlan plan;
  const std::size_t n = static_cast<std::size_t>(layout.size());
  plan.unresolved_bound.assign(n, 0.0);
  if (!(m.real() > 1) || !(x_hi > x_lo)) return plan;
  std::vector<Candidate> candidates;
  throw_if_cancelled(cancel);
  const std::vector<mie::ResonanceBracket> brackets = mie::resonance_brackets(m.real(), x_lo, x_hi);
  throw_if_cancelled(cancel);
  for (const auto& br : brackets) {
    if (candidates.size() % 1024 == 0) throw_if_cancelled(cancel);
    Candidate c;
    c.bracket = br;
    const double x0 = 0.5 * (br.x_lo + br.x_hi);
    if (x0 < x_lo || x0 > x_hi || !(br.width_estimate > 0)) continue;
    c.estimate = resonance_bound(layout, br.order, x0, br.width_estimate, br.width_estimate, near(x0));
    c.share = worst_share(c.estimate, allowed);
    candidates.push_back(std::move(c));
  }
  plan.bracketed = candidates.size();
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.share > b.share; });
  // Locate from the largest estimate down until the rest's estimates sum to a
  // quarter of the allowed error (in batches, located in parallel).
  Vec rest(n, 0.0);
  for (const auto& c : candidates) add(rest, c.estimate);
  std::size_t count = 0;
  while (count < candidates.size() && !within(rest, allowed, 0.25)) {
    throw_if_cancelled(cancel);
    const std::size_t first = count;
    while (count < candidates.size() && count < first + 64) add(rest, candidates[count++].estimate, -1);
    tbb::parallel_for(first, count, [&](std::size_t i) {
      Candidate& c = candidates[i];
      c.pole = mie::locate_resonance(c.bracket, m);
      c.located = true;
    });
  }
  plan.located = count;
  // Exact bounds of the located poles that lie in the range.
  Vec unresolved = rest;
  std::vector<std::size_t> located;
  for (std::size_t i = 0; i < count; ++i) {
    Candidate& c = candidates[i];
    const double x0 = c.pole.pole.real();
    if (x0 < x_lo || x0 > x_hi) continue;
    if (c.pole.half_width() >= kSampledHalfWidth) continue;  // the panels' own nodes resolve it
    c.bound = resonance_bound(layout, c.pole.order, x0, std::abs(c.pole.residue), c.pole.half_width(), near(x0));
    c.share = worst_share(c.bound, allowed);
    add(unresolved, c.bound);
    located.push_back(i);
  }
  std::stable_sort(located.begin(), located.end(),
                   [&](std::size_t a, std::size_t b) { return candidates[a].share > candidates[b].share; });
  std::vector<std::size_t> chosen;
  for (std::size_t i : located) {
    if (within(unresolved, allowed, 0.5)) break;
    const Candidate& c = candidates[i];
    if (c.pole.half_width() < narrowest_resolvable(c.pole.pole.real())) continue;
    chosen.push_back(i);
    add(unresolved, c.bound, -1);
  }
  if (!within(unresolved, allowed, 1.0))
    plan.short_of = "resonances narrower than double precision resolves (half-width < 1e5 eps x) may contribute " +
                    io::significant(worst_share(unresolved, allowed), 3) + " times their share of the tolerance";
  if (chosen.size() > max_resolved) {
    // The tolerance is out of reach.  chosen is in decreasing order of bound:
    // the largest keep their panels (bounding them instead is ~100x looser,
    // the bounds being worst cases), the others stay bounded, and the
    // refinement stops where its quadrature error falls below their bound
    // (Refinement::settled).
    plan.short_of = too_costly(chosen.size(), max_resolved);
    for (std::size_t j = max_resolved; j < chosen.size(); ++j) add(unresolved, candidates[chosen[j]].bound);
    chosen.resize(max_resolved);
  }
  std::sort(chosen.begin(), chosen.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].pole.pole.real() < candidates[b].pole.pole.real();
  });
  for (std::size_t j = 0; j < chosen.size(); ++j) {
    const double x0 = candidates[chosen[j]].pole.pole.real();
    const double left = j > 0 ? candidates[chosen[j - 1]].pole.pole.real() : -1e300;
    const double right = j + 1 < chosen.size() ? candidates[chosen[j + 1]].pole.pole.real() : 1e300;
    const double reach = reach_of(x0, left, right, breakpoints_x);
    const auto& pole = candidates[chosen[j]].pole;
    if (!(reach > 1e-12 * x0)) {
      add(unresolved, candidates[chosen[j]].bound);  // on a breakpoint of the density: bounded
      continue;
    }
    plan.resolved.push_back({pole, reach});
  }
  if (plan.short_of.empty() && !within(unresolved, allowed, 1.0))
    plan.short_of = "resonances on a breakpoint of the size distribution may contribute " +
                    io::significant(worst_share(unresolved, allowed), 3) + " times their share of the tolerance";
  plan.unresolved_bound = unresolved;
  return plan;
}

}  // namespace attenuvis::weather::detail
