// Section 5: visibility-graph performance, measured in this run: pairs/s of
// the scoring engine against a raw Embree occlusion loop over the same pairs
// (the ceiling), and error against run time for range pruning (measured on
// the city by section_city.cpp).
#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "attenuvis/validation/visgraph_benchmark.hpp"
#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "attenuvis/visgraph/visibility.hpp"
#include "sections.hpp"

namespace attenuvis::validation::detail {

namespace {
namespace vg = attenuvis::visgraph;

// Pairs per second of the engine against the raw Embree loops on the five
// layouts, for one thread and for the run's threads.
void layout_throughput(Context& ctx, Section& s) {
  const bool quick = ctx.options.quick;
  const int repeats = quick ? 1 : 2;  // best of two: the job stays within its four minutes
  s.text("Speed is reported as a ratio to a raw Embree occlusion loop over the same unordered pairs, measured in "
         "the same run on the same machine (visgraph::raw_visible_pairs: 16-wide packets, and single rays). The "
         "engine computes degree plus S_S for four sigma values (clear, rain 8, advection fog, dry snow 4) in the "
         "same pass, and decides whole blocks of pairs without rays by exact from-region culling (a pair of node "
         "clusters whose joint hull meets no triangle is all in sight; one planar or solid convex occluder crossing "
         "every segment between them blocks all): the columns say which share of the pairs each way decided. "
         "Culling never changes a result (the tests compare it bit for bit with casting every pair). Best of " +
         std::to_string(repeats) + " runs. Machine: see the preamble.");
  Table t{"performance_pairs",
          "Pairs per second: scoring engine (degree + 4 conditions) against raw Embree occlusion on the same pairs",
          {"scene", "spacing [m]", "nodes", "pairs", "threads", "engine [M pairs/s]", "raw packets16 [M pairs/s]",
           "raw single rays [M pairs/s]", "engine / raw packets16", "culled in sight [%]", "culled blocked [%]",
           "cast [%]", "visible pairs agree"},
          {}, ""};
  std::vector<int> thread_counts = {1};
  if (ctx.threads > 1) thread_counts.push_back(ctx.threads);
  const std::vector<double> spacings = quick ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.5};
  double worst_ratio = 1e300, best_rate = 0;
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const vg::Mesh mesh = vg::classic_layout(k);
    const vg::Scene scene(mesh);
    for (double h : spacings) {
      vg::NodeGridOptions nopt;
      nopt.spacing = h;
      nopt.walkable = {"floor"};
      const auto eyes = vg::generate_nodes(scene, nopt).eyes;
      for (int th : thread_counts) {
        ctx.step("performance", "layout " + std::to_string(k) + ", " + format_number(h, 2) + " m, " +
                                    std::to_string(th) + " thread(s)");
        // Shared with the visgraph_throughput benchmark
        // (validation/visgraph_benchmark.hpp): the seed's printed sigmas,
        // engine and raw packets interleaved repeat by repeat.
        ThroughputOptions o;
        o.threads = th;
        o.repeats = repeats;
        const Throughput m = measure_throughput(scene, eyes, o);
        const double te = m.engine.best_s, tp = m.packets16.best_s, ts = m.single.best_s;
        const double pairs = double(m.pairs);
        t.add_row({std::to_string(k) + " " + vg::classic_layout_name(k), h, eyes.size(), m.pairs, th,
                   Cell(pairs / te / 1e6, 4), Cell(pairs / tp / 1e6, 4), Cell(pairs / ts / 1e6, 4), Cell(tp / te, 3),
                   Cell(100.0 * double(m.culled_visible) / pairs, 3), Cell(100.0 * double(m.culled_blocked) / pairs, 3),
                   Cell(100.0 * double(m.cast) / pairs, 3),
                   m.visible_agree() ? "yes"
                                     : "NO (" + std::to_string(m.visible_engine) + " vs " +
                                           std::to_string(m.visible_packets16) + ")"});
        worst_ratio = std::min(worst_ratio, tp / te);
        best_rate = std::max(best_rate, pairs / te);
      }
    }
  }
  add_table(ctx, s, t);
  ctx.set("performance.worst_engine_over_raw", worst_ratio);
  ctx.set("performance.best_engine_mpairs_s", best_rate / 1e6);
  s.summary.push_back("layouts: engine up to " + sig(best_rate / 1e6, 4) + " M pairs/s; engine/raw-Embree ratio >= " +
                      sig(worst_ratio, 3));
}

// The city's exact all-to-all, as the city section measured it.
void city_timing(Context& ctx, Section& s, const CityPerformance& city) {
  s.text("City (see the city section): exact all-to-all over " + std::to_string(city.city_nodes) + " nodes, " +
         std::to_string(city.city_pairs) + " pairs, degree + 3 conditions: " + sig(city.city_exact_seconds, 3) + " s (" +
         sig(city.city_pairs / city.city_exact_seconds / 1e6, 4) + " M pairs/s) on " + std::to_string(ctx.threads) +
         " thread(s); exact culling decided " + sig(100.0 * city.city_culled_visible / city.city_pairs, 3) +
         "% of the pairs in sight and " + sig(100.0 * city.city_culled_blocked / city.city_pairs, 3) +
         "% blocked without a ray, and " + sig(100.0 * city.city_cast / city.city_pairs, 3) + "% were cast.");
  ctx.set("performance.city_cast_fraction", double(city.city_cast) / double(city.city_pairs));
}

// Range pruning on the city: error against run time, one row per tolerance.
void pruning_table(Context& ctx, Section& s, const CityPerformance& city) {
  Table p{"performance_pruning",
          "Range pruning on the city: error against run time, S_S for " + city.prune_condition + " (sigma " +
              sig(city.prune_sigma, 4) + " 1/m); reference = the exact run of the city section",
          {"tolerance eps", "pruning radius [m]", "pairs cast", "fraction of all pairs", "time [s]",
           "speed-up vs exact run", "max |S_S error|", "certified bound (max over nodes)", "nodes over the bound"},
          {},
          "The bound: every skipped partner lies beyond R = ln(1/eps)/sigma, so contributes at most eps; the "
          "engine reports pruned partners x eps per node (visgraph/visibility.hpp). The exact run also computed "
          "degree and two more conditions, so the speed-up slightly flatters pruning."};
  for (const auto& r : city.prune) {
    if (r.skipped) {
      p.add_row({Cell(r.prune_below, 2), Cell(r.radius_m, 4), "-", "-", "not run", "-", "0 (radius > city diagonal " +
                 format_number(city.city_diameter_m, 4) + " m: nothing to prune)", "0", 0});
      continue;
    }
    if (r.not_applied)
      p.add_row({Cell(r.prune_below, 2), format_number(r.radius_m, 4) + " (not applied: exact pass run)", r.pairs_cast,
                 Cell(double(r.pairs_cast) / double(city.city_pairs), 3), Cell(r.seconds, 3), "-",
                 Cell(r.max_abs_error, 3), Cell(r.max_bound, 3), r.bound_violations});
    else
      p.add_row({Cell(r.prune_below, 2), Cell(r.radius_m, 4), r.pairs_cast, Cell(double(r.pairs_cast) / double(city.city_pairs), 3),
                 Cell(r.seconds, 3), Cell(city.city_exact_seconds / r.seconds, 3), Cell(r.max_abs_error, 3),
                 Cell(r.max_bound, 3), r.bound_violations});
    ctx.set("performance.prune_" + format_number(r.prune_below, 2) + ".max_error", r.max_abs_error);
    ctx.set("performance.prune_" + format_number(r.prune_below, 2) + ".violations", double(r.bound_violations));
  }
  add_table(ctx, s, p);
  for (const auto& r : city.prune)
    if (r.not_applied) {
      s.text("Where a row says 'not applied', the engine judged pruning slower than the exact culled pass and ran "
             "that instead, with every column exact (its words: " + r.note + "). Its time is for S_S of this one "
             "condition, against the exact run's degree and three conditions, so no speed-up is claimed.");
      break;
    }
}

// Whether every pruned score stayed within its certified bound.
void pruning_verdict(Section& s, const CityPerformance& city) {
  std::size_t viol = 0;
  for (const auto& r : city.prune) viol += r.bound_violations;
  if (viol == 0)
    s.agree("at every tolerance the measured S_S error stays within the certified bound at every node.");
  else
    s.disagree(std::to_string(viol) + " node results exceed the certified pruning bound: a defect in the engine.");
  std::string line = "city: exact " + sig(city.city_exact_seconds, 3) + " s";
  for (const auto& r : city.prune)
    if (!r.skipped)
      line += "; eps " + sig(r.prune_below, 2) + ": " + sig(r.seconds, 3) + " s, max err " + sig(r.max_abs_error, 2) +
              " <= bound " + sig(r.max_bound, 2);
  s.summary.push_back(line);
}

}  // namespace

void section_performance(Context& ctx, Section& s, const CityPerformance& city) {
  layout_throughput(ctx, s);
  floors_table(ctx, s);
  if (city.city_nodes == 0) {
    s.missing("the city section did not run, so there is no city timing or pruning study.");
    return;
  }
  city_timing(ctx, s, city);
  pruning_table(ctx, s, city);
  pruning_verdict(s, city);
}

}  // namespace attenuvis::validation::detail
