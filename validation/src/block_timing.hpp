// Timing in alternating blocks of calls by the thread's CPU time, shared by
// the comparisons of the Mie core with other cores (mie_baseline.cpp,
// mie_miev0.cpp).  See attenuvis/validation/mie_baseline.hpp for why: CPU time
// leaves out the time the thread waits for a core on a shared machine, and the
// minimum over alternating blocks is the block least disturbed by the rest.
#pragma once

#include <time.h>

#include <algorithm>
#include <array>
#include <limits>
#include <chrono>

namespace attenuvis::validation::timing {

// Results are added here so that the timed calls cannot be optimised away.
inline volatile double g_sink = 0;

// CPU time of the calling thread, in seconds.
inline double thread_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Calls per block so that one block of f() lasts about min_seconds.
template <class F>
long calls_per_block(F&& f, double min_seconds) {
  long reps = 1;
  for (;;) {
    const double t0 = thread_seconds();
    double acc = 0;
    for (long i = 0; i < reps; ++i) acc += f();
    g_sink = g_sink + acc;
    const double dt = thread_seconds() - t0;
    if (dt >= min_seconds || reps > (1L << 30)) return reps;
    reps = dt > 0 ? std::max(reps * 2, static_cast<long>(reps * 1.2 * min_seconds / dt)) : reps * 16;
  }
}

// ns per call of one block of `reps` calls of f().
template <class F>
double block_ns(F&& f, long reps) {
  const double t0 = thread_seconds();
  double acc = 0;
  for (long i = 0; i < reps; ++i) acc += f();
  const double dt = thread_seconds() - t0;
  g_sink = g_sink + acc;
  return dt / static_cast<double>(reps) * 1e9;
}

// ns per call of each of the functions: the calls per block of each sized to
// about min_block_seconds, then `blocks` rounds in which each runs one block
// in turn; each function's time is its minimum over the rounds.
template <class... F>
std::array<double, sizeof...(F)> alternating_min_ns(double min_block_seconds, int blocks, const F&... f) {
  const std::array<long, sizeof...(F)> reps{calls_per_block(f, min_block_seconds)...};
  std::array<double, sizeof...(F)> best;
  best.fill(std::numeric_limits<double>::infinity());
  for (int b = 0; b < std::max(1, blocks); ++b) {
    std::size_t i = 0;
    ((best[i] = std::min(best[i], block_ns(f, reps[i])), ++i), ...);
  }
  return best;
}

// ns per call of one block of `reps` calls of f() in wall-clock time (for
// work spread over several threads, whose CPU times add up).
template <class F>
double wall_block_ns(F&& f, long reps) {
  const auto t0 = std::chrono::steady_clock::now();
  double acc = 0;
  for (long i = 0; i < reps; ++i) acc += f();
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  g_sink = g_sink + acc;
  return dt / static_cast<double>(reps) * 1e9;
}

}  // namespace attenuvis::validation::timing
