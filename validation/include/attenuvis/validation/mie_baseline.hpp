// Speed of the Mie core against an earlier build of itself, measured in the
// same run.  The earlier core is a shared library built from a given commit by
// validation/bench/baseline/build_mie_baseline.sh and loaded with dlopen; its
// only exported symbol is the C function attenuvis_mie_baseline_sphere.
//
// Timing: for each (x, m) the two cores are timed in alternating blocks of
// calls (each block lasts at least min_block_seconds of the thread's CPU
// time), and each core's time is the minimum over the blocks.  On a shared
// machine the load changes from block to block; CPU time leaves out the time
// the thread waits for a core, alternating exposes both cores to the same
// remaining interference (caches, the sibling hardware thread), and the
// minimum is the block least disturbed by it.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/validation/mie_accuracy.hpp"
#include "attenuvis/validation/shared_library.hpp"

namespace attenuvis::validation {

// The Mie core of an earlier commit, loaded from its shared library to be timed
// beside the current one.
class MieBaseline {
 public:
  /// Loads the library; throws std::runtime_error naming the path and the
  /// loader's message if it cannot be loaded or lacks the entry point.
  explicit MieBaseline(const std::string& library_path);

  /// The earlier core's sphere(x, m); throws std::runtime_error if it threw.
  MieQuantities sphere(double x, std::complex<double> m, int* terms = nullptr) const;
  const std::string& path() const { return library_.path(); }

 private:
  SharedLibrary library_;
};

// The grid of size parameters and indices, and the timing blocks, of a speed table.
struct SpeedOptions {
  std::vector<double> xs = {0.1, 1, 10, 100, 1e3, 1e4, 1e5, 1e6};
  std::vector<std::complex<double>> ms = {{1.0001, 0.0}, {1.33, 1e-8}, {1.5, 0.1}, {10.0, 10.0}};
  double min_block_seconds = 2e-3;
  int blocks = 15;  ///< per core, alternating
  /// Error against the 50-digit referee is measured for x <= this (cost).
  double max_referee_x = 1e4;
};

// One cell of a speed table: ns per call of each core, and their errors.
struct SpeedCell {
  double x = 0;
  std::complex<double> m;
  double ns_current = 0, ns_baseline = 0;
  double err_current = -1, err_baseline = -1;  ///< -1: not measured (x above max_referee_x)
  int terms_current = 0, terms_baseline = 0;
  double speedup() const { return ns_baseline / ns_current; }
};

/// An error of a speed table as printed: "%.1e", or "-" where it was not
/// measured (negative, as SpeedCell's and Miev0Cell's -1).
std::string measured_error_text(double err);

// Times sphere() against the earlier core on every cell of `options`, in
// alternating blocks of thread CPU time.
std::vector<SpeedCell> mie_speed_vs_baseline(const MieBaseline& baseline, const SpeedOptions& options = {});

/// Throughput over many spheres (x uniform in [x_min, x_max], one index):
/// ns per sphere of the baseline's sphere() in a loop, the current sphere() in
/// a loop, and the current spheres() on one thread and on `threads` threads
/// (0: all hardware threads); same alternating-block timing as above (the
/// many-threads figure in wall-clock time).  spheres() on one thread is also
/// timed with each vector instruction set this CPU runs (the first is the one
/// chosen by default).
struct BatchSpeed {
  double x_min = 0.01, x_max = 100;
  std::complex<double> m{1.33, 1e-8};
  std::size_t count = 20000;
  double ns_baseline = 0, ns_single = 0, ns_batch = 0, ns_batch_threads = 0;
  unsigned threads = 0;  ///< for the many-threads figure; 0 = hardware_concurrency() (set on return)
  bool identical = false;  ///< spheres() equal to sphere() bit for bit
  std::vector<std::string> instruction_sets;  ///< spheres_instruction_sets()
  std::vector<double> ns_batch_by_set;        ///< one thread, per instruction set
  bool identical_by_set = false;              ///< every instruction set gives the same bits
};
/// The size parameters of the many-spheres timings: `count` values uniform in
/// [x_min, x_max] from a fixed seed, the same in every run and every comparison.
std::vector<double> batch_size_parameters(double x_min, double x_max, std::size_t count);
BatchSpeed mie_batch_vs_baseline(const MieBaseline& baseline, BatchSpeed setup, int blocks = 5);
std::string format_batch_speed(const BatchSpeed& b);

/// Table: one row per x, per index: current ns, baseline ns, speed-up, errors.
std::string format_speed_vs_baseline(const std::vector<SpeedCell>& cells, const std::string& baseline_name);

}  // namespace attenuvis::validation
