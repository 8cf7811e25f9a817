// Regression test of `attenuvis reproduce --quick`: runs the CLI once into a
// temporary directory and checks the key numbers of key.json against values
// whose origin is stated next to each check:
//   * the seed paper (/work/shared/seed-paper.tex: Schwartz, Vinnikov & Federici,
//     SimAUD 2021) for the sigma table at 550 nm;
//   * 2500 cells of 1 m^2 minus each layout's obstacle footprint for the five
//     layouts' node counts;
//   * physics bounds that hold for any correct visibility graph (S_S <= degree,
//     S_S >= degree * exp(-sigma * longest sight line), monotonicity in sigma);
//   * the report's own documented rules (P1/P2/P3 choice, S_A definitions);
//   * the Mie module's accuracy requirement (within 1e-10 of its 50-digit
//     referee, mie/include/attenuvis/mie.hpp) and the published Mie tables;
//   * the page's structure: the verdict table first, the seed's story in its
//     order, every figure present, long tables folded, no project-internal words.
// No number computed by attenuvis is pasted in as an expected value.
//
// The quick run takes over 30 s on 2 cores: tagged [slow] (Release CI only).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct QuickRun {
  fs::path dir;
  int status = -1;
  std::string log;
  nlohmann::json key;
  bool baseline = false;     // run with --mie-baseline (the earlier core built from the history)
  std::string baseline_why;  // why not, or the build's log when it failed
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The earlier Mie core built from the git history (a single file, about 2 s
// of g++) into `dir`: the library's path, or empty with the reason in `why`.
fs::path build_baseline(const fs::path& dir, std::string& why) {
  const fs::path root = fs::path(ATTENUVIS_TEST_DATA_DIR).parent_path().parent_path();
  const std::string history = "git -C '" + root.string() + "' rev-parse --quiet --verify '78ee94c^{commit}' >/dev/null 2>&1";
  if (std::system(history.c_str()) != 0) {
    why = "commit 78ee94c is not in this checkout's history (a source archive or a shallow clone)";
    return {};
  }
  const fs::path lib_dir = dir / "mie_baseline_78ee94c";
  const fs::path log = dir / "baseline-build.log";
  const std::string build = "sh '" + (root / "validation/bench/baseline/build_mie_baseline.sh").string() +
                            "' 78ee94c '" + lib_dir.string() + "' >'" + log.string() + "' 2>&1";
  if (std::system(build.c_str()) != 0) {
    why = "building the 78ee94c core failed:\n" + slurp(log);
    return {};
  }
  return lib_dir / "libmie_baseline.so";
}

// The quick reproduction, run once for every test case of this file, with
// the earlier Mie core when the history has it (so that one run checks the
// report and the Mie section's speed tables).
const QuickRun& quick_run() {
  static QuickRun run = [] {
    QuickRun r;
    const fs::path base = fs::temp_directory_path() / ("attenuvis-reproduce-test-" + std::to_string(::getpid()));
    fs::remove_all(base);
    fs::create_directories(base);
    r.dir = base / "out";
    const fs::path lib = build_baseline(base, r.baseline_why);
    r.baseline = !lib.empty();
    const fs::path log = base / "reproduce.log";
    std::string cmd = std::string("'") + ATTENUVIS_CLI + "' reproduce --quick --threads 2 --out '" + r.dir.string() + "'";
    if (r.baseline) cmd += " --mie-baseline '" + lib.string() + "'";
    cmd += " >'" + log.string() + "' 2>&1";
    r.status = std::system(cmd.c_str());
    r.log = slurp(log);
    if (fs::exists(r.dir / "key.json")) r.key = nlohmann::json::parse(slurp(r.dir / "key.json"));
    if (r.baseline) fs::remove_all(lib.parent_path());  // the earlier core was needed for the run only
    return r;
  }();
  return run;
}

double key(const std::string& name) {
  const auto& k = quick_run().key;
  INFO("key.json entry " << name);
  REQUIRE(k.contains(name));
  REQUIRE(k.at(name).is_number());
  return k.at(name).get<double>();
}

// Rows of a CSV table of the report (header + rows, plain fields only).
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream f(p);
  REQUIRE(f.good());
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> header;
  for (std::string line; std::getline(f, line);) {
    std::vector<std::string> fields;
    std::string cur;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) fields.push_back(cur), cur.clear();
      else cur += c;
    }
    fields.push_back(cur);
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

// The Mie section's speed tables of a run with the earlier core.  Their
// numbers are timings and are not checked (tests never time things); what is
// checked is their shape, the key numbers' presence, and a property that is
// not a timing: spheres() gives sphere()'s bits with every instruction set.
void check_speed_tables(const fs::path& out) {
  const auto k = nlohmann::json::parse(slurp(out / "key.json"));
  for (const char* name : {"mie.speedup.per_call_min", "mie.speedup.per_call_median", "mie.speedup.per_call_max",
                           "mie.speedup.sphere_loop", "mie.speedup.batch_one_thread", "mie.speedup.batch_threads"}) {
    INFO(name);
    REQUIRE(k.contains(name));
    CHECK(std::isfinite(k.at(name).get<double>()));
    CHECK(k.at(name).get<double>() > 0);
  }
  CHECK(k.at("mie.speedup.per_call_min") <= k.at("mie.speedup.per_call_median"));
  CHECK(k.at("mie.speedup.per_call_median") <= k.at("mie.speedup.per_call_max"));
  CHECK(k.at("mie.batch.bit_identical") == 1.0);
  // Quick mode: three x (rows) by the four indices of the benchmark (columns).
  const auto per_call = read_csv(out / "mie_speedup_per_call.csv");
  REQUIRE(per_call.size() == 3);
  for (const auto& row : per_call) {
    CHECK(row.size() == 5);
    CHECK(row.count("m = 1.33+1e-8i") == 1);
  }
  CHECK(read_csv(out / "mie_speedup_cells.csv").size() == 12);
  const auto batch = read_csv(out / "mie_batch_speed.csv");
  REQUIRE(batch.size() >= 4);  // the earlier loop, sphere() loop, spheres() one thread, spheres() threads
  CHECK(batch.front().at("speed-up") == "1");
  const std::string html = slurp(out / "report.html");
  CHECK_THAT(html, Catch::Contains("against the 78ee94c core") && !Catch::Contains("is not measured in this run"));
}

}  // namespace

// One test case, so that ctest (one process per test case) runs the quick
// reproduction once; each SECTION checks one part of its output.
TEST_CASE("reproduce --quick: report files and key numbers", "[validation][slow]") {
  SECTION("finishes and writes report.html, its figures and tables") {
    const QuickRun& r = quick_run();
    INFO("attenuvis reproduce --quick output:\n" << r.log);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(r.dir / "report.html"));
    REQUIRE(fs::exists(r.dir / "key.json"));
    // Nothing left of the staging directory.
    for (const auto& e : fs::directory_iterator(r.dir))
      CHECK(e.path().filename().string().rfind(".reproduce-staging", 0) != 0);
    // Every PNG and CSV the page links to exists and is not empty, and every
    // section is there and available (no "not available in this build").
    const std::string html = slurp(r.dir / "report.html");
    std::set<std::string> linked;
    const std::regex ref(R"re((?:src|href)="([^"#]+\.(?:png|csv))")re");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), ref); it != std::sregex_iterator(); ++it)
      linked.insert((*it)[1]);
    std::size_t pngs = 0, csvs = 0;
    for (const auto& f : linked) {
      INFO(f);
      CHECK(fs::exists(r.dir / f));
      if (fs::exists(r.dir / f)) CHECK(fs::file_size(r.dir / f) > 0);
      (f.size() > 4 && f.substr(f.size() - 4) == ".png" ? pngs : csvs)++;
    }
    CHECK(pngs >= 10);
    CHECK(csvs >= 10);
    CHECK(html.find("not available in this build") == std::string::npos);
    CHECK(r.log.find("MISSING") == std::string::npos);
  }

  SECTION("the page: verdict table first, the seed's order, every figure, long tables folded") {
    const QuickRun& r = quick_run();
    REQUIRE(r.status == 0);
    const std::string html = slurp(r.dir / "report.html");
    // The verdict opens the page: before any other section and any figure.
    const auto verdict = html.find("<section id=\"verdict\"");
    REQUIRE(verdict != std::string::npos);
    CHECK(verdict < html.find("<img"));
    CHECK(verdict < html.find("<section id=\"guide\""));
    // Then the seed's story in the paper's order (scenes, layouts, city), its
    // next step (space syntax in weather), the sigma values, and what the seed
    // does not have (Mie validation, performance).
    std::size_t last = verdict;
    for (const char* id : {"scenes", "layouts", "city", "space_syntax", "weather", "haze", "mie", "performance"}) {
      INFO("section " << id);
      const auto at = html.find(std::string("<section id=\"") + id + "\"");
      REQUIRE(at != std::string::npos);
      CHECK(at > last);
      last = at;
    }
    // One verdict row per agree/differ/missing line counted in key.json, each
    // linking to a section of the page.
    const std::string table = html.substr(verdict, html.find("</section>", verdict) - verdict);
    const std::regex row(R"re(<td class="v (agree|disagree|missing)">)re");
    const auto rows = std::distance(std::sregex_iterator(table.begin(), table.end(), row), std::sregex_iterator());
    CHECK(rows == key("closing.agree") + key("closing.differ") + key("closing.missing"));
    CHECK(rows >= 8);
    const std::regex link(R"re(<a href="#([a-z_]+)">)re");
    std::size_t links = 0;
    for (auto it = std::sregex_iterator(table.begin(), table.end(), link); it != std::sregex_iterator(); ++it, ++links)
      CHECK(html.find("<section id=\"" + (*it)[1].str() + "\"") != std::string::npos);
    CHECK(links == static_cast<std::size_t>(rows));
    // Every figure drawn is on the page, and every image the page shows was drawn.
    std::set<std::string> shown;
    const std::regex img(R"re(<img src="([^"]+)")re");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it)
      shown.insert((*it)[1]);
    std::size_t pngs = 0;
    for (const auto& e : fs::directory_iterator(r.dir))
      if (e.path().extension() == ".png") {
        ++pngs;
        INFO(e.path().filename().string());
        CHECK(shown.count(e.path().filename().string()) == 1);
      }
    CHECK(shown.size() == pngs);
    // The 3D views of the scenes (seed Figs. vg_cases and vg_case_city).
    CHECK(shown.count("scenes_layouts.png") == 1);
    CHECK(shown.count("scenes_city.png") == 1);
    // Tables longer than 15 rows are folded; every table scrolls in its own box.
    std::size_t tables = 0;
    for (auto at = html.find("<table id="); at != std::string::npos; at = html.find("<table id=", at + 1)) {
      ++tables;
      const auto end = html.find("</table>", at);
      REQUIRE(end != std::string::npos);
      std::size_t rows_in = 0;
      for (auto tr = html.find("<tr>", at); tr < end; tr = html.find("<tr>", tr + 1)) ++rows_in;
      const std::string before = html.substr(0, at);
      INFO("table at byte " << at << " with " << rows_in - 1 << " rows");
      CHECK(before.size() >= 20);
      CHECK(before.substr(before.size() - 20).find("<div class=\"scroll\">") != std::string::npos);
      if (rows_in - 1 > 15) {
        const auto open = before.rfind("<details>"), close = before.rfind("</details>");
        CHECK(open != std::string::npos);
        CHECK((close == std::string::npos || close < open));
      }
    }
    CHECK(tables >= 10);
    // The text speaks to a reader who has only the seed paper: no tracker words.
    const std::string text = std::regex_replace(html, std::regex("<[^>]*>"), " ");
    for (const char* word : {"issue", "ticket", "session"}) {
      const std::regex w(std::string("\\b") + word, std::regex::icase);
      std::smatch m;
      const bool found = std::regex_search(text, m, w);
      const std::size_t from = found ? static_cast<std::size_t>(std::max<long>(0, m.position() - 80)) : 0;
      INFO("'" << word << "' in the page's text: ..." << (found ? text.substr(from, 160) : std::string()) << "...");
      CHECK_FALSE(found);
    }
  }

  SECTION("the seed's sigma table at 550 nm") {
    REQUIRE(quick_run().status == 0);
    // Seed paper, Sec. Results / Visibility Graph Case: clear weather sigma = 0.00015 1/m,
    // the same in both conventions (no power law involved).
    CHECK(key("weather.sigma.clear.itu") == Approx(0.00015).epsilon(1e-12));
    CHECK(key("weather.sigma.clear.seed") == Approx(0.00015).epsilon(1e-12));

    // Seed paper, Sec. Results, text of Fig. vg_weather: rain sigma = 0.0045 and snow
    // sigma = 0.0374, printed to 2 and 3 significant digits; the seed reads P.1817-1's
    // power laws as 1/km ("seed" convention), so these must match to half a unit of
    // the last printed digit there, and the "itu" reading (dB/km) must be exactly
    // ln(10)/10 of it (1 dB/km = ln(10)/10 1/km).
    const double half_unit_rain = 0.00005, half_unit_snow = 0.00005;
    CHECK(std::abs(key("weather.sigma.rain_8.seed") - 0.0045) <= half_unit_rain);
    CHECK(std::abs(key("weather.sigma.snow_dry_4.seed") - 0.0374) <= half_unit_snow);
    const double db = std::log(10.0) / 10.0;
    CHECK(key("weather.sigma.rain_8.itu") == Approx(key("weather.sigma.rain_8.seed") * db).epsilon(1e-9));
    CHECK(key("weather.sigma.snow_dry_4.itu") == Approx(key("weather.sigma.snow_dry_4.seed") * db).epsilon(1e-9));

    // Seed paper, Sec. Methodology / Fog: heavy advection fog 0.02874311 and moderate
    // radiation fog 0.00863808 1/m at 550 nm (Mie over the P.1817-1 presets), 7
    // significant digits.  Our converged integral (contour, error < 1e-9) differs by
    // -1.3e-4 and +5.3e-4 relative.  The report states (a) that the difference is real
    // (above our error), (b) that the water index does not explain it (the spread of
    // the indices it tries, table weather_fog_refractive_index, is far smaller), and
    // (c) whether a fixed-step midpoint sum of the same integral with the seed's
    // n' = 1.33 errs by as much (table weather_fog_seed_quadrature): with the quick
    // run's steps it does for radiation fog (3.5e-3) but not quite for advection fog
    // (1.1e-4 against 1.3e-4), and the verdict must say which.  Each claim is checked here.
    const auto variants = read_csv(quick_run().dir / "weather_fog_refractive_index.csv");
    REQUIRE(!variants.empty());
    struct Fog {
      const char* tag;
      const char* preset;
      const char* name;
      double seed;
    };
    for (const Fog f : {Fog{"fog_advection", "advection", "heavy advection fog", 0.02874311},
                        Fog{"fog_radiation", "radiation", "moderate radiation fog", 0.00863808}}) {
      const double ours = key(std::string("weather.sigma.") + f.tag + ".itu");
      CHECK(ours == key(std::string("weather.sigma.") + f.tag + ".seed"));  // Mie: no convention
      const double err = key(std::string("weather.sigma.") + f.tag + ".error");
      double spread = 0;
      int found = 0;
      for (const auto& v : variants) {
        if (v.at("fog") != f.name) continue;
        spread = std::max(spread, std::abs(std::stod(v.at("sigma [1/m]")) - ours));
        ++found;
      }
      const std::string q = std::string("weather.fog_seed_quadrature.") + f.preset;
      const double seed_rel = key(q + ".seed_rel"), midpoint = key(q + ".midpoint_worst_rel");
      INFO(f.name << ": ours " << ours << " +- " << err << ", seed " << f.seed << ", index spread " << spread
                  << ", seed vs converged (m = 1.33) " << seed_rel << ", midpoint sums up to " << midpoint);
      CHECK(found >= 3);
      CHECK(err <= 1e-9 * ours);                          // converged (contour_extinction.hpp)
      CHECK(key(q + ".converged_rel_error") <= 1e-9);
      CHECK(std::abs(ours - f.seed) > 100 * err);         // (a) the difference is real
      CHECK(spread < 0.5 * std::abs(ours - f.seed));      // (b) the index does not explain it
      CHECK(key(q + ".midpoint_explains") == (std::abs(seed_rel) <= midpoint ? 1.0 : 0.0));  // (c) as stated
      CHECK(midpoint > 0.1 * std::abs(seed_rel));         // same order: a coarse quadrature is a candidate
      CHECK(std::abs(seed_rel) < 1e-3);                   // agreement in the 4th significant digit
    }
  }

  SECTION("the five layouts' node counts and degree statistics") {
    REQUIRE(quick_run().status == 0);
    // 2500 cells of 1 m^2 minus each layout's obstacle footprint (the obstacles of
    // the seed's Fig. vg_cases as visgraph/generators.hpp places them).
    const double nodes[5] = {2424, 2000, 2400, 2000, 2460};
    // Longest sight line in a 50 m x 50 m square: 50 sqrt(2) m (plus nothing in z:
    // all eyes at 1.7 m), so every visible pair has C >= exp(-sigma * 50 sqrt 2).
    const double longest = 50 * std::sqrt(2.0);
    const double sigma_clear = key("weather.sigma.clear.itu");
    for (int i = 0; i < 5; ++i) {
      const std::string p = "layouts." + std::to_string(i) + ".";
      INFO("layout " << i);
      CHECK(key(p + "nodes") == nodes[i]);
      const double dmin = key(p + "degree_min"), dmax = key(p + "degree_max"), dmean = key(p + "degree_mean");
      CHECK(dmin >= 1);
      CHECK(dmax <= nodes[i] - 1);
      CHECK(dmin <= dmean);
      CHECK(dmean <= dmax);
      // Handshake lemma: edges = sum of degrees / 2 = mean * nodes / 2, an integer.
      const double edges = key(p + "edges");
      CHECK(edges == Approx(dmean * nodes[i] / 2).epsilon(1e-12));
      CHECK(edges == std::floor(edges));
      // S_S <= degree at every node, in every condition (C <= 1).
      CHECK(key(p + "ss_above_degree") == 0);
      // Clear weather: degree * exp(-sigma d_max) <= S_S <= degree, node by node,
      // hence for the extremes too.
      const double smin = key(p + "ss_clear_min"), smax = key(p + "ss_clear_max");
      CHECK(smax <= dmax);
      CHECK(smin <= dmin);
      CHECK(smax >= dmax * std::exp(-sigma_clear * longest));
      CHECK(smin >= dmin * std::exp(-sigma_clear * longest));
      // S_S decreases with sigma at every node, so its max and min do too.
      double last_max = smax, last_min = smin;
      // sigma: clear 0.00015 < rain 8 (itu) < rain 8 (seed) < dry snow 4 (seed).
      for (const char* tag : {"rain8_itu", "rain8_seed", "snowdry4_seed"}) {
        INFO(tag);
        const double mx = key(p + "ss_" + std::string(tag) + "_max"), mn = key(p + "ss_" + std::string(tag) + "_min");
        CHECK(mx <= last_max);
        CHECK(mn <= last_min);
        last_max = mx, last_min = mn;
      }
    }
    // Seed paper, caption of Fig. count: the third layout (single block) has the most connections.
    CHECK(key("layouts.most_edges_index") == 2);
  }

  SECTION("city points and the two S_A definitions") {
    REQUIRE(quick_run().status == 0);
    const double n = key("city.nodes");
    CHECK(n > 1000);
    // The report's rule: P1 is the corner at the central junction with the lowest
    // clear S_S, P2 the one with the highest, so S_S(P1) <= S_S(P2) in clear weather.
    CHECK(key("city.P1.clear.ss") <= key("city.P2.clear.ss"));
    for (const char* p : {"P1", "P2", "P3"}) {
      INFO(p);
      const std::string k = std::string("city.") + p;
      const double deg = key(k + ".degree");
      for (const char* c : {"clear", "snowdry4_itu", "snowdry4_seed"}) {
        INFO(c);
        const double ss = key(k + "." + c + ".ss");
        CHECK(ss <= deg);
        CHECK(key(k + "." + c + ".sa_degree") == Approx(ss / deg).epsilon(1e-12));
        CHECK(key(k + "." + c + ".sa_all") == Approx(ss / n).epsilon(1e-12));
      }
      CHECK(key(k + ".snowdry4_seed.ss") < key(k + ".snowdry4_itu.ss"));  // seed's sigma is 4.34x larger
      CHECK(key(k + ".snowdry4_itu.ss") < key(k + ".clear.ss"));
    }
    // The seed's conclusion (P3 best in clear, P1 beats P3 in snow), as the report
    // evaluates it, is consistent with the S_S values it reports, in both conventions.
    for (const char* conv : {"itu", "seed"}) {
      INFO(conv);
      const bool clear_p3 = key("city.P3.clear.ss") > key("city.P1.clear.ss");
      const bool snow_p1 = key(std::string("city.P1.snowdry4_") + conv + ".ss") >
                           key(std::string("city.P3.snowdry4_") + conv + ".ss");
      CHECK(key(std::string("city.conclusion_survives.") + conv) == ((clear_p3 && snow_p1) ? 1 : 0));
    }
  }

  SECTION("Mie validation numbers") {
    REQUIRE(quick_run().status == 0);
    // Published tables (tests/data/mie/*.csv): MIEV0 19 cases x (5 + 7 angles x 2),
    // Wiscombe 1979 8 x 4 + 2 x 37 x 2, Bohren & Huffman 3 + 21 x 4, Du 2004 13 x 2 twice.
    CHECK(key("mie.published.entries") == 19 * 5 + 19 * 7 * 2 + 8 * 4 + 2 * 37 * 2 + 3 + 21 * 4 + 13 * 2 + 13 * 2);
    CHECK(key("mie.published.unexplained") == 0);
    CHECK(key("mie.published.within_digits") + key("mie.published.documented") == key("mie.published.entries"));
    // The Mie module's requirement: double within 1e-10 of the 50-digit referee
    // everywhere on the map.
    CHECK(key("mie.map.cells") >= 20);
    CHECK(key("mie.map.cells_above_1e-10") == 0);
    CHECK(key("mie.map.max_error") <= 1e-10);
    CHECK(key("mie.time.max_error.default") <= 1e-10);
  }

  SECTION("the Mie section's speed tables with the earlier core, or without it the page says how to get one") {
    const QuickRun& r = quick_run();
    REQUIRE(r.status == 0);
    if (!r.baseline) {
      WARN(r.baseline_why << ": the speed tables are not tested");
      CHECK_FALSE(r.key.contains("mie.speedup.per_call_min"));
      CHECK_FALSE(fs::exists(r.dir / "mie_speedup_per_call.csv"));
      const std::string html = slurp(r.dir / "report.html");
      CHECK_THAT(html, Catch::Contains("build_mie_baseline.sh") &&
                           Catch::Contains("attenuvis reproduce --mie-baseline build/mie_baseline_78ee94c/libmie_baseline.so"));
      return;
    }
    check_speed_tables(r.dir);
  }
}

// An earlier Mie core that cannot be loaded stops the job before any work:
// the message names the option, the file and the loader's reason, and the
// output directory is not even created.
TEST_CASE("reproduce: an earlier Mie core that cannot be loaded stops the job with nothing written", "[validation]") {
  const fs::path base = fs::temp_directory_path() / ("attenuvis-reproduce-baseline-" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const fs::path not_a_library = base / "not_a_library.so";
  std::ofstream(not_a_library) << "this is text, not a shared library\n";
  struct Case {
    fs::path library;
    const char* reason;  // part of the loader's message (glibc's dlerror)
  };
  for (const Case& c : {Case{base / "missing" / "libmie_baseline.so", "No such file"},
                        Case{not_a_library, "cannot load the baseline Mie library"}}) {
    const fs::path out = base / "out";
    const fs::path log = base / "log";
    const std::string cmd = std::string("'") + ATTENUVIS_CLI + "' reproduce --quick --threads 2 --out '" +
                            out.string() + "' --mie-baseline '" + c.library.string() + "' >'" + log.string() +
                            "' 2>&1";
    const int status = std::system(cmd.c_str());
    const std::string text = slurp(log);
    INFO(c.library << ": " << text);
    CHECK(status != 0);
    CHECK_THAT(text, Catch::Contains("attenuvis: error: --mie-baseline") && Catch::Contains(c.library.string()) &&
                         Catch::Contains(c.reason) && Catch::Contains("no report written"));
    CHECK_FALSE(fs::exists(out));
  }
  fs::remove_all(base);
}

TEST_CASE("reproduce: an output name taken by a directory stops the job before its work, with nothing moved", "[validation]") {
  const fs::path dir = fs::temp_directory_path() / ("attenuvis-reproduce-taken-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "key.json");  // where the job's key numbers would go
  const fs::path log = dir.string() + ".log";
  const std::string cmd = std::string("'") + ATTENUVIS_CLI + "' reproduce --quick --threads 2 --out '" +
                          dir.string() + "' >'" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string text = slurp(log);
  INFO(text);
  CHECK(status != 0);
  CHECK_THAT(text, Catch::Contains("attenuvis: error:") && Catch::Contains("key.json") &&
                       Catch::Contains("not a regular file"));
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"key.json"});  // no table, figure or report moved in
  fs::remove_all(dir);
  fs::remove(log);
}

