// Private to the reproduction job: the context every section receives and the
// section entry points (one file each: section_mie.cpp, section_weather.cpp,
// section_optics.cpp, section_haze.cpp, section_layouts.cpp, section_city.cpp,
// section_performance.cpp).
#pragma once

#include <chrono>
#include <complex>
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <memory>

#include "attenuvis/validation/report.hpp"
#include "attenuvis/visgraph/space_syntax.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/validation/reproduce.hpp"

namespace attenuvis::validation {
class MieBaseline;
}

namespace attenuvis::validation::detail {

// A single progress line on a terminal (rewritten in place), one line per
// step otherwise, so logs stay readable (heartbeat.cpp).
class Progress {
 public:
  Progress(std::ostream* os, bool tty);
  void step(const std::string& section, const std::string& what);
  void done();
  double elapsed() const;

 private:
  std::ostream* os_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

struct Context {
  ReproduceOptions options;
  std::string dir;                       // staging directory: every table/figure goes here
  int threads = 1;                       // threads the run may use (already applied to TBB)
  Progress* progress = nullptr;
  std::map<std::string, double>* key = nullptr;
  std::vector<Paragraph>* closing = nullptr;   // the report's closing note
  const MieBaseline* mie_baseline = nullptr;   // earlier Mie core to time against (options.mie_baseline)

  void step(const std::string& section, const std::string& what) const {
    if (progress) progress->step(section, what);
  }
  void set(const std::string& name, double value) const { (*key)[name] = value; }
  // A line of the closing note: kind "agree", "disagree", "missing" or "text".
  void conclude(const std::string& kind, std::string text) const { closing->push_back(Paragraph{kind, std::move(text)}); }
};

// The σ values every visibility section uses, computed once by the weather
// section (in both conventions) and read by the layout and city sections.
struct SeedConditions {
  // Names in the seed's order: clear, rain 8 mm/h, heavy advection fog,
  // moderate radiation fog, dry snow 4 mm/h.
  struct Row {
    std::string name;        // e.g. "rain 8 mm/h"
    std::string condition;   // the condition as the grammar writes it, e.g. "rain:8" (labels, keys)
    weather::Condition weather;  // the same condition as a value
    double seed_published;   // the seed paper's σ [1/m]
    std::string seed_where;  // where in the seed paper
    double itu = 0.0;        // σ [1/m], convention itu (power laws in dB/km)
    double seed = 0.0;       // σ [1/m], convention seed (power laws read as 1/km)
    double error_itu = 0.0;  // error estimate [1/m] as reported by the weather module
    double error_seed = 0.0;
    std::string model;       // model used, as the weather module names it
  };
  std::vector<Row> rows;
  const Row* find(const std::string& condition) const {
    for (const auto& r : rows)
      if (r.condition == condition) return &r;
    return nullptr;
  }
};

// The seed's five conditions with their published σ (value and place in the
// paper); itu/seed left NaN for the weather section to fill.
SeedConditions seed_published_conditions();

// One σ to run a visibility graph with.  `tag` is file-name safe.
struct VgCondition {
  std::string label;   // for tables and figure titles, e.g. "rain 8 mm/h (seed convention)"
  std::string tag;     // e.g. "rain8_seed"
  std::string short_label;  // for figure panels, e.g. "rain 8, seed"
  std::string condition;  // grammar string, e.g. "rain:8"
  std::string convention; // "itu", "seed" or "both" (σ the same in both)
  double sigma = 0;       // 1/m
  // The label in score column names ("sum:" + column_label): the condition as
  // the command line writes it, with "@itu" or "@seed" where the two
  // conventions give different σ — the same scheme as `attenuvis vg`'s
  // sum:LABEL / avg:LABEL columns.
  std::string column_label() const { return convention == "both" ? condition : condition + "@" + convention; }
};
// The σ values of `condition` for the visibility sections: one entry when
// both conventions give the same σ, two (itu, then seed) otherwise.  Needs
// the σ the weather section computed (throws std::logic_error before that).
std::vector<VgCondition> vg_conditions(const SeedConditions& seed, const std::string& condition);

// Numbers the city section measures for the performance section (the city
// scene is built once).
struct CityPerformance {
  std::size_t city_nodes = 0;
  std::uint64_t city_pairs = 0;
  double city_exact_seconds = 0;   // all-to-all, degree + all conditions, exact
  std::uint64_t city_culled_visible = 0, city_culled_blocked = 0, city_cast = 0;  // how its pairs were decided
  struct PruneRow {
    double prune_below = 0, radius_m = 0, seconds = 0;
    std::uint64_t pairs_cast = 0;
    double max_abs_error = 0;      // max over nodes |S_S(eps) - S_S(exact)|
    double max_bound = 0;          // max over nodes of the certified bound
    std::size_t bound_violations = 0;
    bool skipped = false;          // radius beyond the city: identical to exact, not run
    bool not_applied = false;      // the engine ran exact: pruning would have been slower (note says why)
    std::string note;              // the engine's pruning_note
  };
  double city_diameter_m = 0;
  std::vector<PruneRow> prune;
  std::string prune_condition;
  double prune_sigma = 0;
};

// The city's lines of sight and its points P1-P3, kept by the city section's
// exact pass for the space-syntax section (one pass serves both).
struct CityLines {
  std::vector<Eigen::Vector3d> eyes;
  std::unique_ptr<visgraph::VisibilityGraph> graph;  // null until the city section has run
  std::vector<std::size_t> points;                   // node indices of P1, P2, P3
  std::vector<std::string> point_names;
};

// The city's S_S under urban haze: the city section sums it in its own pass
// (the same scene and nodes) and writes it to city_nodes.csv; the Haze
// section draws it.
struct CityHaze {
  std::string condition = "haze:urban:rh=95";
  double sigma = 0;            // 1/m at 550 nm
  std::string column, clear_column;  // city_nodes.csv columns of S_S under haze and in clear weather
  double mean_ss_clear = 0, mean_ss_haze = 0;
  std::size_t nodes = 0;
};

void section_mie(Context& ctx, Section& s);
// The Mie section's speed tables against an earlier core (ctx.mie_baseline),
// or the sentence saying how to get them (section_mie_speed.cpp).
void section_mie_speed(Context& ctx, Section& s);
// The Mie section's layered spheres: referee grid, published checks, time
// per call (section_mie_layered.cpp).
void section_mie_layered(Context& ctx, Section& s);
void section_weather(Context& ctx, Section& s, SeedConditions& seed);
void section_optics(Context& ctx, Section& s);  // section_optics.cpp
void section_layouts(Context& ctx, Section& s, const SeedConditions& seed);
void section_city(Context& ctx, Section& s, const SeedConditions& seed, CityPerformance& perf, CityLines& lines,
                  CityHaze& haze);
void section_space_syntax(Context& ctx, Section& s, const SeedConditions& seed, CityLines& city);  // section_space_syntax.cpp
void section_haze(Context& ctx, Section& s, const CityHaze& city);  // section_haze.cpp
// The performance section's table of the engine against its two floors
// (performance_floors.cpp).
void floors_table(Context& ctx, Section& s);
void section_performance(Context& ctx, Section& s, const CityPerformance& city);

// Shared helpers (reproduce.cpp).
// Writes a table's CSV into the staging directory and adds it to the section.
Table& add_table(Context& ctx, Section& s, Table t);
// Writes a data file (per-node scores) into the staging directory: one column
// per header entry, all columns the same length; numbers in round-trip form.
void write_data_csv(Context& ctx, const std::string& file, const std::vector<std::string>& header,
                    const std::vector<const std::vector<double>*>& columns);
std::string sig(double v, int digits = 4);     // format_number shorthand for prose
std::string index_label(std::complex<double> m);  // "1.33+1e-8i", "1.5": tables and figure labels
double seconds_since(std::chrono::steady_clock::time_point t0);

}  // namespace attenuvis::validation::detail
