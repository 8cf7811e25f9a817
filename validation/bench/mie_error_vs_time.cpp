// Error against run time of the Mie core: for x in the decades
// 1e-3 ... 1e6 and m in {1.0001, 1.33+1e-8i, 1.5+0.1i, 10+10i}, the median time
// per call and the largest relative error against the 50-digit referee of
//   default       attenuvis::mie::sphere (terms until converged)
//   wiscombe      attenuvis with Wiscombe's term count N = x + 4.05 x^(1/3) + 2
//   conventional  a textbook Bohren–Huffman double loop (Wiscombe's N, D_n downward
//                 from |mx| + 15), see mie_conventional.hpp — not MIEV0 itself
//   double        attenuvis with Precision::double_precision (the fast mode)
// The last column is default time / conventional time, both measured in this run.
//
// With --baseline LIB (default: build/mie_baseline_78ee94c/libmie_baseline.so
// when present) it then times the default mode against an earlier build of the
// core (LIB from validation/bench/baseline/build_mie_baseline.sh, by default
// commit 78ee94c), interleaved in the same run, and prints the
// speed-up per x and index, then the throughput of many spheres (x uniform in
// [0.01, 100], m = 1.33+1e-8i): the baseline's sphere() in a loop against the
// current sphere() and spheres() (see attenuvis/validation/mie_baseline.hpp).
//
// With --miev0 LIB (default: build/miev0/libmiev0.so when present) it also
// times Wiscombe's MIEV0 itself, built from the user's copy of its source by
// validation/bench/miev0/build_miev0.sh: per call against the default and the
// Wiscombe-count modes, with each one's error against the referee, and over
// the same many spheres and over narrow ranges of x around 0.1, 1, 10 and 100
// (see attenuvis/validation/mie_miev0.hpp).
//
// Usage: mie_error_vs_time [out.csv] [--quick] [--max-x X] [--baseline LIB] [--miev0 LIB] [--speed-only]
//   out.csv       default out/mie_error_vs_time.csv (written atomically)
//   --quick       stop at x = 1e4 (a few seconds); the full table needs the 50-digit
//                 referee at x = 1e5 and 1e6, about 30 s per m at 1e6.
//   --speed-only  skip the error-vs-time table (with --baseline)
#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "attenuvis/validation/mie_accuracy.hpp"
#include "attenuvis/validation/mie_baseline.hpp"
#include "attenuvis/validation/mie_miev0.hpp"

namespace {
using namespace attenuvis::validation;

struct Args {
  std::string out = "out/mie_error_vs_time.csv";
  ErrorTimeOptions options;
  std::string baseline_path, miev0_path;
  bool speed_only = false;
};

// False for an unknown option, after saying so on stderr.
bool parse(int argc, char** argv, Args& args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      const double keep = args.options.max_x;
      args.options = quick_error_time_options();
      if (keep < args.options.max_x) args.options.max_x = keep;
    } else if (a == "--max-x" && i + 1 < argc) {
      args.options.max_x = std::stod(argv[++i]);
    } else if (a == "--baseline" && i + 1 < argc) {
      args.baseline_path = argv[++i];
    } else if (a == "--miev0" && i + 1 < argc) {
      args.miev0_path = argv[++i];
    } else if (a == "--speed-only") {
      args.speed_only = true;
    } else if (!a.empty() && a[0] == '-') {
      std::cerr << "mie_error_vs_time: unknown option " << a
                << "\nusage: mie_error_vs_time [out.csv] [--quick] [--max-x X] [--baseline LIB] [--miev0 LIB] "
                   "[--speed-only]\n";
      return false;
    } else {
      args.out = a;
    }
  }
  return true;
}

// A library the build scripts leave in the build tree, if it is there and no
// path was given.
void guess_library(std::string& path, const char* argv0, const char* folder, const char* file) {
  if (!path.empty()) return;
  const auto p = std::filesystem::path(argv0).parent_path() / ".." / folder / file;
  std::error_code ec;
  if (std::filesystem::is_regular_file(p, ec)) path = p.lexically_normal().string();
}

void error_vs_time_table(const Args& args) {
  const auto rows = mie_error_vs_time(args.options);
  std::cout << "\nerror: max over Qext, Qsca, Qabs, g, Qback of |q - q_ref| / max(|q_ref|, 1e-4 Qext)"
               " against the 50-digit referee\n\n"
            << format_error_vs_time(rows);
  write_error_vs_time_csv(args.out, rows);
  std::cout << "\nwrote " << args.out << "\n";
}

void baseline_speed(const std::string& path, const SpeedOptions& speed) {
  const MieBaseline baseline(path);
  std::cout << "\nper call, default accuracy, against " << path << "\n"
            << format_speed_vs_baseline(mie_speed_vs_baseline(baseline, speed), "baseline") << "\n"
            << format_batch_speed(mie_batch_vs_baseline(baseline, BatchSpeed{}));
}

void miev0_speed(const std::string& path, const SpeedOptions& speed) {
  const Miev0Library miev0(path);
  std::cout << "\nper call against MIEV0 (" << path << ")\n" << format_speed_vs_miev0(mie_speed_vs_miev0(miev0, speed));
  // The goal's range, then narrow ranges around the per-call table's x.
  const double ranges[][2] = {{0.01, 100}, {0.05, 0.15}, {0.5, 1.5}, {5, 15}, {50, 150}};
  for (const auto& r : ranges) {
    Miev0Batch b;
    b.x_min = r[0], b.x_max = r[1];
    std::cout << "\n" << format_batch_vs_miev0(mie_batch_vs_miev0(miev0, b));
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Args args;
    if (!parse(argc, argv, args)) return 2;
    guess_library(args.baseline_path, argv[0], "mie_baseline_78ee94c", "libmie_baseline.so");
    guess_library(args.miev0_path, argv[0], "miev0", "libmiev0.so");
    if (args.speed_only && args.baseline_path.empty() && args.miev0_path.empty()) {
      std::cerr << "mie_error_vs_time: --speed-only needs --baseline LIB or --miev0 LIB\n";
      return 2;
    }
    std::cout << "Mie core timings (" << timing_machine_description() << ")\n";
    if (!args.speed_only) error_vs_time_table(args);
    SpeedOptions speed;
    speed.xs.erase(std::remove_if(speed.xs.begin(), speed.xs.end(), [&](double x) { return x > args.options.max_x; }),
                   speed.xs.end());
    if (args.baseline_path.empty())
      std::cout << "\nno baseline core: build one with validation/bench/baseline/build_mie_baseline.sh "
                   "(commit 78ee94c by default) and pass --baseline LIB\n";
    else
      baseline_speed(args.baseline_path, speed);
    if (!args.miev0_path.empty()) miev0_speed(args.miev0_path, speed);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mie_error_vs_time: error: " << e.what() << "\n";
    return 1;
  }
}
