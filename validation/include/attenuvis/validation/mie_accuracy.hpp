// Accuracy and speed of the attenuvis Mie core measured against its own
// 50-digit referee: the error map over (x, m) and the error-against-run-time
// table.  The reproduction report and the benchmark
// validation/bench/mie_error_vs_time.cpp both call these functions.
//
// Error measure: for each of Qext, Qsca, Qabs, g, Qback,
//     e_q = |q_double - q_ref| / max(|q_ref|, 1e-4 * Qext_ref),
// i.e. the relative error, except that where q itself is below 1e-4 Qext the
// error is taken relative to 1e-4 Qext; e_q <= 1e-10 is then exactly the
// requirement "within 1e-10 relative, with an absolute floor of 1e-14 Qext where
// the quantity itself is that small".  max_rel_error is the largest e_q; it is
// +infinity when a result is NaN or infinite.
//
// Cost: the referee evaluates the series in cpp_bin_float_50 and takes about
// 1000 times as long as a double call; its cost grows like the number of terms
// (~x).  At x = 1e6 one referee call takes seconds to tens of seconds, so the
// options carry a max_x and quick_error_time_options() stops at x = 1e4.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::validation {

/// The five quantities the accuracy requirement names.
struct MieQuantities {
  double qext = 0, qsca = 0, qabs = 0, g = 0, qback = 0;
};

/// The five quantities of a double-precision result of the core.
MieQuantities mie_quantities(const mie::Efficiencies<double>& e);

/// Largest normalised error of `got` against `ref` (see file comment).
double mie_max_relative_error(const MieQuantities& got, const MieQuantities& ref);

/// The 50-digit referee's quantities, rounded to double.
MieQuantities mie_referee_quantities(double x, std::complex<double> m);

// ------------------------------------------------------------ error map
struct ErrorMapCell {
  double x = 0, n = 0, k = 0;
  double max_rel_error = 0;
};

/// Default double evaluation against the referee on the grid xs × ms.
std::vector<ErrorMapCell> mie_error_map(const std::vector<double>& xs,
                                        const std::vector<std::complex<double>>& ms);

// ------------------------------------------------------------ error vs time
struct ErrorTimeOptions {
  /// Size parameters; default: the decades 1e-3 ... 1e6.
  std::vector<double> xs = {1e-3, 1e-2, 1e-1, 1, 10, 100, 1e3, 1e4, 1e5, 1e6};
  /// Refractive indices; default: the stress set {1.0001, 1.33+1e-8i, 1.5+0.1i, 10+10i}.
  std::vector<std::complex<double>> ms = {
      {1.0001, 0.0}, {1.33, 1e-8}, {1.5, 0.1}, {10.0, 10.0}};
  /// Points with x above this are skipped (referee cost, see file comment).
  double max_x = 1e6;
  /// Each timing sample repeats the call until it lasts at least this long.
  double min_sample_seconds = 2e-3;
  /// Median of this many samples.
  int samples = 5;
  /// Also time the textbook baseline (mie_conventional.hpp).
  bool include_conventional = true;
};

/// Same table, stopping at x = 1e4 with 3 samples: a few seconds in total.
ErrorTimeOptions quick_error_time_options();

// One sphere of the error-against-time table: each term rule's error and time.
struct ErrorTimeRow {
  double x = 0;
  std::complex<double> m;
  /// "default", "double" (Precision::double_precision, the fast mode),
  /// "wiscombe" (attenuvis with Wiscombe's term count) and "conventional"
  /// (the textbook baseline).
  std::string mode;
  double ns_per_call = 0;     ///< median over the samples
  double max_rel_error = 0;   ///< against the 50-digit referee
  int terms = 0;              ///< terms summed by this mode
};

/// Times every mode at every (x, m) and measures its error; the referee is
/// evaluated once per point.  Rows are ordered by m, then x, then mode.
std::vector<ErrorTimeRow> mie_error_vs_time(const ErrorTimeOptions& options = {});

/// Writes the rows as CSV (header x,m_re,m_im,mode,ns_per_call,max_rel_error,terms)
/// atomically: to a temporary file in the same directory, then renamed.
void write_error_vs_time_csv(const std::string& path, const std::vector<ErrorTimeRow>& rows);

/// Human-readable table (one line per x and m, one column pair per mode), with
/// the ratio of the default time to the conventional baseline's.
std::string format_error_vs_time(const std::vector<ErrorTimeRow>& rows);

/// Description of the machine the timings were taken on (CPU model, hardware
/// threads, current 1-minute load average, compiler).
std::string timing_machine_description();

}  // namespace attenuvis::validation
