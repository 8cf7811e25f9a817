// The Mie section's speed against an earlier build of the core: the speed-up
// per call of mie::sphere over x and m, and the throughput over many spheres
// of sphere() in a loop and of spheres() (mie_baseline.hpp measures both; this
// file only turns the measurements into tables and key numbers).  Without an
// earlier core the section says how to get these tables.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "attenuvis/validation/mie_accuracy.hpp"
#include "attenuvis/validation/mie_baseline.hpp"
#include "sections.hpp"

namespace attenuvis::validation::detail {
namespace {

// build_mie_baseline.sh leaves the library in .../mie_baseline_COMMIT/; the
// directory names the commit when it follows that pattern.
std::string baseline_label(const std::string& library_path) {
  const std::string dir = std::filesystem::path(library_path).parent_path().filename().string();
  const std::string prefix = "mie_baseline_";
  if (dir.size() > prefix.size() && dir.compare(0, prefix.size(), prefix) == 0)
    return "the " + dir.substr(prefix.size()) + " core";
  return "the earlier core";
}

// Quick mode: three x and a few short blocks (about a second); full mode: the
// benchmark's own grid, x = 0.1 ... 1e6, nine blocks per core instead of the
// benchmark's fifteen (13.0 s -> 9.1 s measured on the 2-core CI machine, to
// keep the main job near its four minutes).
SpeedOptions speed_options(bool quick) {
  SpeedOptions o;
  o.blocks = 9;
  if (quick) {
    o.xs = {0.1, 10, 1e3};
    o.blocks = 3;
    o.min_block_seconds = 1e-3;
    o.max_referee_x = 1e3;
  }
  return o;
}

// Rows x, columns m, each cell the earlier core's time over the current one's.
void per_call_table(Context& ctx, Section& s, const std::string& label, const std::string& machine) {
  const SpeedOptions o = speed_options(ctx.options.quick);
  ctx.step("mie", "speed per call against " + label + " (" + std::to_string(o.xs.size() * o.ms.size()) + " cells)");
  const auto cells = mie_speed_vs_baseline(*ctx.mie_baseline, o);

  Table t{"mie_speedup_per_call",
          "Speed-up per call of attenuvis::mie::sphere (double, default options) against " + label +
              ": its time per call divided by this build's, by size parameter x (rows) and refractive index m "
              "(columns)",
          {"x"},
          {},
          "Measured in this run, in one process, one thread: for each (x, m) the two cores run in alternating "
          "blocks of calls (each block at least " +
              sig(o.min_block_seconds * 1e3, 2) + " ms of the thread's CPU time), " + std::to_string(o.blocks) +
              " blocks each; each core's time is its fastest block, in thread CPU time, so that time spent waiting "
              "for a core on a shared machine counts for neither. Earlier core: " +
              ctx.mie_baseline->path() +
              " (validation/bench/baseline/build_mie_baseline.sh, g++ -O3, loaded with dlopen). Machine: " + machine +
              "."};
  for (const auto& m : o.ms) t.header.push_back("m = " + index_label(m));
  std::vector<double> speedups;
  std::vector<double> col_x, col_n, col_k, col_ns, col_ns_base, col_ratio, col_err, col_err_base, col_terms,
      col_terms_base;
  for (double x : o.xs) {
    std::vector<Cell> row{Cell(x, 3)};
    for (const auto& m : o.ms) {
      const auto it = std::find_if(cells.begin(), cells.end(), [&](const SpeedCell& c) { return c.x == x && c.m == m; });
      if (it == cells.end()) {
        row.push_back("-");
        continue;
      }
      row.push_back(Cell(it->speedup(), 3));
      speedups.push_back(it->speedup());
      col_x.push_back(x), col_n.push_back(m.real()), col_k.push_back(m.imag());
      col_ns.push_back(it->ns_current), col_ns_base.push_back(it->ns_baseline), col_ratio.push_back(it->speedup());
      col_err.push_back(it->err_current < 0 ? NAN : it->err_current);
      col_err_base.push_back(it->err_baseline < 0 ? NAN : it->err_baseline);
      col_terms.push_back(it->terms_current), col_terms_base.push_back(it->terms_baseline);
    }
    t.add_row(std::move(row));
  }
  add_table(ctx, s, t);
  write_data_csv(ctx, "mie_speedup_cells.csv",
                 {"x", "n", "k", "ns_per_call", "ns_per_call_earlier", "speedup", "max_rel_error",
                  "max_rel_error_earlier", "terms", "terms_earlier"},
                 {&col_x, &col_n, &col_k, &col_ns, &col_ns_base, &col_ratio, &col_err, &col_err_base, &col_terms,
                  &col_terms_base});
  s.data("mie_speedup_cells.csv",
         "every cell of the table: ns per call of both cores, the speed-up, each core's largest relative error "
         "against the 50-digit reference (x <= " +
             sig(o.max_referee_x, 2) + "; nan above) and the terms each summed.");

  std::sort(speedups.begin(), speedups.end());
  const double lo = speedups.front(), hi = speedups.back(), median = speedups[speedups.size() / 2];
  ctx.set("mie.speedup.per_call_min", lo);
  ctx.set("mie.speedup.per_call_median", median);
  ctx.set("mie.speedup.per_call_max", hi);
  const std::string line = "speed-up per call against " + label + ": " + sig(lo, 3) + "x to " + sig(hi, 3) +
                           "x (median " + sig(median, 3) + "x) over x " + sig(o.xs.front(), 2) + " ... " +
                           sig(o.xs.back(), 2) + " and " + std::to_string(o.ms.size()) + " indices";
  s.summary.push_back(line);
  s.text(line + ".");
}

// ns per sphere and speed-up of each way of evaluating many spheres.
void batch_table(Context& ctx, Section& s, const std::string& label, const std::string& machine) {
  BatchSpeed setup;
  int blocks = 5;
  if (ctx.options.quick) setup.count = 2000, blocks = 2;
  setup.threads = static_cast<unsigned>(std::max(1, ctx.threads));
  ctx.step("mie", "throughput of " + std::to_string(setup.count) + " spheres against " + label);
  const BatchSpeed b = mie_batch_vs_baseline(*ctx.mie_baseline, setup, blocks);

  Table t{"mie_batch_speed",
          "Many spheres: " + std::to_string(b.count) + " spheres, x uniform in [" + sig(b.x_min, 2) + ", " +
              sig(b.x_max, 3) + "], m = " + index_label(b.m) + "; time per sphere and speed-up against " + label +
              "'s sphere() in a loop",
          {"evaluation", "ns per sphere", "speed-up"},
          {},
          "Measured in this run, in one process: the ways of evaluating the same spheres run in alternating blocks "
          "(one pass over all spheres each), " +
              std::to_string(blocks) +
              " blocks each, fastest block; thread CPU time except the many-threads row (wall clock). spheres() "
              "evaluates the spheres eight per vector instruction, with the best instruction set this CPU runs "
              "unless told otherwise. Machine: " +
              machine + "."};
  auto add = [&](const std::string& what, double ns) { t.add_row({what, Cell(ns, 4), Cell(b.ns_baseline / ns, 3)}); };
  add(label + ", sphere() in a loop", b.ns_baseline);
  add("this build, sphere() in a loop", b.ns_single);
  add("this build, spheres(), one thread" +
          (b.instruction_sets.empty() ? std::string() : " (chooses " + b.instruction_sets.front() + ")"),
      b.ns_batch);
  for (std::size_t i = 0; i < b.instruction_sets.size(); ++i)
    add("this build, spheres(), one thread, told to use " + b.instruction_sets[i], b.ns_batch_by_set[i]);
  add("this build, spheres(), " + std::to_string(b.threads) + " threads (wall clock)", b.ns_batch_threads);
  add_table(ctx, s, t);

  ctx.set("mie.batch.ns_per_sphere_earlier", b.ns_baseline);
  ctx.set("mie.batch.ns_per_sphere_sphere_loop", b.ns_single);
  ctx.set("mie.batch.ns_per_sphere_spheres", b.ns_batch);
  ctx.set("mie.speedup.sphere_loop", b.ns_baseline / b.ns_single);
  ctx.set("mie.speedup.batch_one_thread", b.ns_baseline / b.ns_batch);
  ctx.set("mie.speedup.batch_threads", b.ns_baseline / b.ns_batch_threads);
  ctx.set("mie.batch.bit_identical", b.identical && b.identical_by_set ? 1.0 : 0.0);
  const std::string line = "many spheres against " + label + "'s sphere() loop: sphere() loop " +
                           sig(b.ns_baseline / b.ns_single, 3) + "x, spheres() on one thread " +
                           sig(b.ns_baseline / b.ns_batch, 3) + "x, on " + std::to_string(b.threads) +
                           " threads " + sig(b.ns_baseline / b.ns_batch_threads, 3) + "x";
  s.summary.push_back(line);
  s.text(line + ". spheres() " +
         (b.identical && b.identical_by_set
              ? "gives sphere()'s results bit for bit on every sphere, with every instruction set."
              : "DOES NOT give sphere()'s results bit for bit on every sphere with every instruction set."));
}

}  // namespace

void section_mie_speed(Context& ctx, Section& s) {
  if (!ctx.mie_baseline) {
    s.text("The speed-up against the earlier Mie core (commit 78ee94c, per call and over many spheres) is not "
           "measured in this run: it needs that core built from the git history, "
           "`bash validation/bench/baseline/build_mie_baseline.sh`, and passed to the job, "
           "`attenuvis reproduce --mie-baseline build/mie_baseline_78ee94c/libmie_baseline.so` "
           "(scripts/main.sh does both).");
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string label = baseline_label(ctx.mie_baseline->path());
  const std::string machine = timing_machine_description();
  s.text("Speed against " + label + " (" + ctx.mie_baseline->path() +
         "), built from the same sources as they were at that commit and timed in this process beside the current "
         "core." +
         (ctx.options.quick ? " QUICK MODE: three size parameters, few and short blocks, 2000 spheres." : ""));
  per_call_table(ctx, s, label, machine);
  batch_table(ctx, s, label, machine);
  ctx.set("time.mie_speed_s", seconds_since(t0));
}

}  // namespace attenuvis::validation::detail
