// The reproduction job: runs the sections in order inside a staging
// directory, draws the figures with matplotlib, writes report.html last and
// only then moves everything into the output directory.
#include "attenuvis/validation/reproduce.hpp"
#include "attenuvis/validation/mie_baseline.hpp"
#include "attenuvis/io/install_paths.hpp"
#include "attenuvis/io/shell.hpp"
#include "attenuvis/io/staged_file.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <unistd.h>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "heartbeat.hpp"
#include "section_scenes.hpp"
#include "sections.hpp"

namespace fs = std::filesystem;

namespace attenuvis::validation {
namespace detail {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string sig(double v, int digits) { return format_number(v, digits); }

std::string index_label(std::complex<double> m) {
  std::string s = format_number(m.real(), 6);
  if (m.imag() != 0) s += "+" + format_number(m.imag(), 3) + "i";
  return s;
}

Table& add_table(Context& ctx, Section& s, Table t) {
  write_table_csv(t, (fs::path(ctx.dir) / (t.id + ".csv")).string());
  return s.table(std::move(t));
}

void write_data_csv(Context& ctx, const std::string& file, const std::vector<std::string>& header,
                    const std::vector<const std::vector<double>*>& columns) {
  if (header.size() != columns.size()) throw std::logic_error("write_data_csv: header/column count differ for " + file);
  const std::size_t n = columns.empty() ? 0 : columns[0]->size();
  std::string text;
  for (std::size_t c = 0; c < header.size(); ++c) text += (c ? "," : "") + header[c];
  text += "\n";
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c]->size() != n) throw std::logic_error("write_data_csv: ragged columns in " + file);
      text += (c ? "," : "") + exact_number((*columns[c])[i]);
    }
    text += "\n";
  }
  write_file_atomically((fs::path(ctx.dir) / file).string(), text);
}

}  // namespace detail

namespace {

using detail::Context;

std::string tail_of_file(const fs::path& p, std::size_t max_chars) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string s = ss.str();
  if (s.size() > max_chars) s = "..." + s.substr(s.size() - max_chars);
  return s;
}

// Draws every figure of the report with one interpreter (matplotlib's import
// costs about a second; once is enough), which forks into `processes` to
// draw.  Any failure fails the job.
void draw_figures(const Report& report, const std::string& dir, int processes, detail::Progress* progress) {
  nlohmann::json spec;
  spec["processes"] = processes;
  spec["figures"] = nlohmann::json::array();
  std::vector<std::string> ids;
  for (const auto& s : report.sections)
    for (const auto& b : s.blocks)
      if (auto f = std::get_if<Figure>(&b)) {
        nlohmann::json j = f->spec;
        j["id"] = f->id;
        spec["figures"].push_back(j);
        ids.push_back(f->id);
      }
  if (ids.empty()) return;
  if (progress) progress->step("figures", "drawing " + std::to_string(ids.size()) + " figures with matplotlib");
  const fs::path spec_path = fs::path(dir) / "figures.json";
  write_file_atomically(spec_path.string(), spec.dump());
  const fs::path log = fs::path(dir) / "figures.log";
  const std::string python = ATTENUVIS_PYTHON;
  const std::string script =
      io::installed_or_source("scripts/report_figures.py", std::string(ATTENUVIS_SCRIPTS_DIR) + "/report_figures.py");
  if (python.empty() || !fs::exists(python))
    throw std::runtime_error("figures: no Python interpreter (ATTENUVIS_PYTHON='" + python +
                             "'); install python3-matplotlib and python3-numpy (scripts/setup.sh)");
  const std::string cmd = "MPLCONFIGDIR=" + io::shell_quote((fs::path(dir) / ".mpl").string()) + " " +
                          io::shell_quote(python) + " " + io::shell_quote(script) + " " + io::shell_quote(spec_path.string()) +
                          " " + io::shell_quote(dir) + " >" + io::shell_quote(log.string()) + " 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0)
    throw std::runtime_error("figures: " + python + " " + script + " failed (status " + std::to_string(rc) +
                             "); no report written. Its output:\n" + tail_of_file(log, 2000));
  for (const auto& id : ids)
    if (!fs::exists(fs::path(dir) / (id + ".png")))
      throw std::runtime_error("figures: " + id + ".png was not drawn; no report written");
  fs::remove(spec_path);
  fs::remove(log);
  fs::remove_all(fs::path(dir) / ".mpl");
}

// The terms every section uses, for a reader who has only the seed paper.
std::vector<Paragraph> reading_guide() {
  return {
      {"text",
       "The seed paper is Schwartz, Vinnikov & Federici, 'Adding Visibility to Visibility Graphs: Weighting Visibility Analysis with Attenuation Coefficients' (SimAUD 2021). It weights "
       "each line of sight of a visibility graph by its contrast ratio C = exp(-sigma d), d the distance in metres "
       "and sigma the extinction coefficient of the weather in 1/m. Per node: the degree is the number of nodes it "
       "sees; S_S is the sum of C over them (equal to the degree when sigma = 0); S_A is S_S divided by a node "
       "count (the seed's equation divides by the degree; the city section shows which divisor its numbers use). "
       "A single-point map shows C from every node to one chosen node, 0 where that node is not in sight."},
      {"text",
       "Two readings of the units. ITU-R P.1817-1 gives rain and snow attenuation as power "
       "laws in dB/km; read that way, they give the 'itu' convention. The seed reads the same numbers as 1/km "
       "('seed' convention), which makes every rain and snow sigma 10 / ln 10 = 4.34 times larger; its printed "
       "sigma values (0.0045 1/m for rain of 8 mm/h, 0.0374 1/m for dry snow of 4 mm/h, Sec. Results) follow that "
       "reading. Where the two differ, the "
       "visibility sections are computed with both. Fog sigma comes from Mie theory and clear weather is a fixed "
       "value, so the conventions do not touch them."},
  };
}

std::string machine_line(int threads) {
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  return cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads, " +
         std::to_string(threads) + " used";
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return buf;
}

// The earlier Mie core to time against, loaded before any work: a library
// that cannot be loaded stops the job before the output directory is touched.
std::unique_ptr<MieBaseline> load_mie_baseline(const std::string& path) {
  if (path.empty()) return nullptr;
  try {
    // An absolute path: dlopen reads a bare file name as a search in the
    // system's library directories, not in the working directory.
    return std::make_unique<MieBaseline>(fs::absolute(path).lexically_normal().string());
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("--mie-baseline: ") + e.what() + " (no report written)");
  }
}

fs::path make_output_directory(const std::string& out_dir) {
  const fs::path out = out_dir.empty() ? fs::path("out") : fs::path(out_dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw std::runtime_error("cannot create output directory '" + out.string() + "': " + ec.message());
  return out;
}

// Every file is written here first, inside the output directory; whatever
// happens before the final move, the staging directory goes away.
class StagingDirectory {
 public:
  explicit StagingDirectory(const fs::path& out) : path_(out / (".reproduce-staging-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~StagingDirectory() {
    std::error_code e;
    fs::remove_all(path_, e);
  }
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Sections run in the order their inputs need (the sigma values first: the
// visibility sections use them) and are shown in the seed paper's order:
// its scenes, the five layouts, the city, then the sigma values behind
// them, then what the seed does not have (Mie validation, performance).
// Their verdicts follow the page's order too.
void run_sections(Context& ctx, Report& report) {
  detail::SeedConditions seed;
  detail::CityPerformance city_perf;
  detail::CityLines city_lines;
  detail::CityHaze city_haze;
  struct Step {
    const char* id;
    const char* title;
    int shown_at;
    std::function<void(Section&)> run;
  };
  const std::vector<Step> steps = {
      {"weather", "Extinction coefficients: the seed's sigma values and the models behind them", 4,
       [&](Section& s) { detail::section_weather(ctx, s, seed); }},
      {"scenes", "The scenes: five classic layouts and a city", 0, [&](Section& s) { detail::section_scenes(ctx, s); }},
      {"layouts", "The five layouts: degree, S_S in clear weather and in weather, single-point maps", 1,
       [&](Section& s) { detail::section_layouts(ctx, s, seed); }},
      {"city", "The city: S_S, P1, P2, P3 and the seed's conclusion", 2,
       [&](Section& s) { detail::section_city(ctx, s, seed, city_perf, city_lines, city_haze); }},
      {"space_syntax", "Space syntax in weather", 3,
       [&](Section& s) { detail::section_space_syntax(ctx, s, seed, city_lines); }},
      {"optics", "Bulk optics of the fogs: scattering, absorption, g, backscatter, lidar ratio, phase function", 5,
       [&](Section& s) { detail::section_optics(ctx, s); }},
      {"haze", "Haze: OPAC aerosols, their growth with humidity, visibility and a city under urban haze", 6,
       [&](Section& s) { detail::section_haze(ctx, s, city_haze); }},
      {"mie", "Mie validation: published tables and a 50-digit reference", 7,
       [&](Section& s) { detail::section_mie(ctx, s); }},
      {"performance", "Visibility-graph performance", 8,
       [&](Section& s) { detail::section_performance(ctx, s, city_perf); }},
  };
  std::vector<std::pair<int, Section>> computed;
  for (const auto& step : steps) {
    Section s;
    s.id = step.id;
    s.title = std::to_string(step.shown_at + 1) + ". " + step.title;
    ctx.step(step.id, "starting");
    const auto ts = std::chrono::steady_clock::now();
    const std::size_t verdicts_before = report.closing.size();
    try {
      step.run(s);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("section '") + step.title + "' failed: " + e.what() +
                               " (no report written)");
    }
    s.seconds = detail::seconds_since(ts);
    report.key["time." + std::string(step.id) + "_s"] = s.seconds;
    // Each verdict links to the section that made it.
    for (std::size_t i = verdicts_before; i < report.closing.size(); ++i) report.closing[i].section = s.id;
    computed.emplace_back(step.shown_at, std::move(s));
  }
  std::stable_sort(computed.begin(), computed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<std::string, int> shown_at;
  for (const auto& step : steps) shown_at[step.id] = step.shown_at;
  std::stable_sort(report.closing.begin(), report.closing.end(), [&](const Paragraph& a, const Paragraph& b) {
    return shown_at[a.section] < shown_at[b.section];
  });
  for (auto& [at, s] : computed) report.sections.push_back(std::move(s));
}

// The verdicts open the page: first their count, then one row each (the
// lines themselves, with the reasons, come from the sections).
void open_with_verdict_count(Report& report) {
  std::size_t agree = 0, disagree = 0, missing = 0;
  for (const auto& p : report.closing) {
    if (p.kind == "agree") ++agree;
    else if (p.kind == "disagree") ++disagree;
    else if (p.kind == "missing") ++missing;
  }
  report.closing.insert(report.closing.begin(),
                        Paragraph{"text", "Of the " + std::to_string(agree + disagree + missing) + " checks, " +
                                              std::to_string(agree) + " agree and " + std::to_string(disagree) +
                                              " differ, each with its reason" +
                                              (missing ? "; " + std::to_string(missing) +
                                                             " could not be made in this build"
                                                       : std::string()) +
                                              "."});
  report.key["closing.agree"] = static_cast<double>(agree);
  report.key["closing.differ"] = static_cast<double>(disagree);
  report.key["closing.missing"] = static_cast<double>(missing);
}

// How the run was made: when, by which command, on what, in how long.
std::string preamble(const ReproduceOptions& options, int threads, double seconds) {
  return std::string("Computed on ") + utc_now() + " by `attenuvis reproduce" + (options.quick ? " --quick" : "") +
         "` on " + machine_line(threads) + "; total " + format_number(seconds, 3) +
         " s. Every number below was computed in this run; the only numbers typed in are the "
         "published values we compare against, each shown with its source." +
         (options.quick ? " QUICK MODE: coarse grids and a small city; the numbers that depend on "
                          "grid size are not the seed's configuration."
                        : "");
}

// The one-screen summary: the run, each section with its own lines, the
// verdict count; and the sections this build could not compute.
void summarise(const Report& report, const ReproduceOptions& options, int threads, ReproduceResult& result) {
  for (const auto& s : report.sections)
    if (!s.available) result.missing.push_back(s.title);
  result.summary.push_back("attenuvis reproduce" + std::string(options.quick ? " --quick" : "") + ": " +
                           format_number(result.seconds, 3) + " s on " + std::to_string(threads) + " thread(s)");
  for (const auto& s : report.sections) {
    result.summary.push_back(s.title + (s.available ? "" : "  [NOT AVAILABLE IN THIS BUILD]") + "  (" +
                             format_number(s.seconds, 3) + " s)");
    for (const auto& line : s.summary) result.summary.push_back("  " + line);
  }
  result.summary.push_back("verdict: " + report.closing.front().text);
}

// Moves everything out of staging into `out`; report.html last, so its
// presence means the whole set is there.  Every destination is checked
// before the first move, so a name taken by a directory or a device stops
// the job with nothing moved.
void move_out_of_staging(const fs::path& staging, const fs::path& out, bool with_report) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(staging))
    if (e.is_regular_file() && e.path().filename() != "report.html") files.push_back(e.path());
  for (const auto& f : files) io::require_regular_or_absent((out / f.filename()).string());
  if (with_report) io::require_regular_or_absent((out / "report.html").string());
  for (const auto& f : files) fs::rename(f, out / f.filename());
  if (with_report) fs::rename(staging / "report.html", out / "report.html");
}

}  // namespace

ReproduceResult reproduce(const ReproduceOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<MieBaseline> mie_baseline = load_mie_baseline(options.mie_baseline);
  const fs::path out = make_output_directory(options.out_dir);
  // The job's fixed outputs are checked before minutes of work, not only
  // when they are moved in (move_outputs checks every file again).
  for (const char* name : {"key.json", "report.html"}) io::require_regular_or_absent((out / name).string());
  const StagingDirectory staging(out);

  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));

  detail::Progress progress(options.progress, options.progress == &std::cerr && ::isatty(2));
  detail::StallTicker ticker(progress, options.progress != nullptr);
  Report report;
  report.title = "attenuvis: reproduction of Schwartz, Vinnikov & Federici (SimAUD 2021) and Mie validation";
  Context ctx;
  ctx.options = options;
  ctx.dir = staging.path().string();
  ctx.threads = threads;
  ctx.progress = &progress;
  ctx.key = &report.key;
  ctx.closing = &report.closing;
  ctx.mie_baseline = mie_baseline.get();

  run_sections(ctx, report);
  open_with_verdict_count(report);
  report.guide = reading_guide();
  if (options.figures) draw_figures(report, staging.path().string(), threads, &progress);

  ReproduceResult result;
  result.seconds = detail::seconds_since(t0);
  report.key["time.total_s"] = result.seconds;
  report.preamble = preamble(options, threads, result.seconds);
  summarise(report, options, threads, result);
  write_key_json(report, (staging.path() / "key.json").string());
  if (options.figures) write_report_html(report, (staging.path() / "report.html").string());

  progress.step("output", "moving files into " + out.string());
  move_out_of_staging(staging.path(), out, options.figures);
  if (options.figures) {
    result.report_path = (out / "report.html").string();
    result.summary.push_back("report: " + result.report_path);
  } else {
    result.summary.push_back("figures skipped: no report.html written (tables and key.json in " + out.string() + ")");
  }
  if (!result.missing.empty()) {
    std::string m = "MISSING (not available in this build):";
    for (const auto& s : result.missing) m += " [" + s + "]";
    result.summary.push_back(m);
  }
  progress.done();
  result.key = report.key;
  return result;
}

}  // namespace attenuvis::validation
