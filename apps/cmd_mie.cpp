// `attenuvis mie`: Lorenz–Mie efficiencies of one sphere (--x, --m), or a
// batch read from stdin (no --x).  Parsing and formatting of the batch live in
// attenuvis/mie/batch.hpp; this file only maps options to library calls.
#include <cstdio>
#include <iostream>
#include <memory>
#include <streambuf>
#include <string>

#include <nlohmann/json.hpp>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie.hpp"
#include "attenuvis/mie/batch.hpp"
#include "commands.hpp"

namespace attenuvis::cli {
namespace {

// Writes to `target` with "attenuvis: error: " before each line, so that the
// batch's "line N: why" messages read like every other error of the program
// (apps/main.cpp).
class ErrorPrefixBuf : public std::streambuf {
 public:
  explicit ErrorPrefixBuf(std::ostream& target) : target_(target) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    if (at_line_start_) target_ << "attenuvis: error: ";
    target_.put(traits_type::to_char_type(c));
    at_line_start_ = traits_type::to_char_type(c) == '\n';
    return c;
  }
  int sync() override {
    target_.flush();
    return 0;
  }

 private:
  std::ostream& target_;
  bool at_line_start_ = true;
};

struct MieArgs {
  double x = 0;
  std::string m = "1.33,0";
  std::string angles;
  std::string terms = "converged";
  std::string working = "auto";
  bool json = false;
};

mie::Options make_options(const MieArgs& a) {
  mie::Options o;
  if (a.terms == "wiscombe") o.terms = mie::TermRule::wiscombe;
  if (a.working == "double") o.precision = mie::Precision::double_precision;
  if (a.working == "extended") o.precision = mie::Precision::extended;
  return o;
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void print_text(const MieArgs& a, std::complex<double> m, const mie::Scattering<double>& s) {
  const auto& q = s.q;
  // The input echoed as the shortest text that reads back to it; results at 17 digits.
  std::cout << "Mie sphere  x = " << io::shortest(a.x) << "  m = " << io::shortest(m.real()) << " + "
            << io::shortest(m.imag()) << "i\n"
            << "  Qext  = " << num(q.qext) << "\n"
            << "  Qsca  = " << num(q.qsca) << "\n"
            << "  Qabs  = " << num(q.qabs) << "\n"
            << "  Qback = " << num(q.qback) << "   (Bohren-Huffman 4|S1(180)|^2/x^2; BHMIE's is this/4pi)\n"
            << "  Qpr   = " << num(q.qpr) << "\n"
            << "  g     = " << num(q.g) << "\n"
            << "  terms = " << q.terms << " (" << a.terms << ")\n";
  if (!s.angles_deg.empty()) {
    std::cout << "  theta_deg  Re S1  Im S1  Re S2  Im S2\n";
    for (std::size_t i = 0; i < s.angles_deg.size(); ++i)
      std::cout << "  " << num(s.angles_deg[i]) << "  " << num(s.s1[i].real()) << "  " << num(s.s1[i].imag())
                << "  " << num(s.s2[i].real()) << "  " << num(s.s2[i].imag()) << "\n";
  }
}

void print_json(const MieArgs& a, std::complex<double> m, const mie::Scattering<double>& s) {
  const auto& q = s.q;
  nlohmann::json j = {{"x", a.x},         {"m", {m.real(), m.imag()}}, {"qext", q.qext}, {"qsca", q.qsca},
                      {"qabs", q.qabs},   {"qback", q.qback},          {"qpr", q.qpr},   {"g", q.g},
                      {"terms", q.terms}, {"term_rule", a.terms}};
  if (!s.angles_deg.empty()) {
    nlohmann::json s1 = nlohmann::json::array(), s2 = nlohmann::json::array();
    for (std::size_t i = 0; i < s.angles_deg.size(); ++i) {
      s1.push_back({s.s1[i].real(), s.s1[i].imag()});
      s2.push_back({s.s2[i].real(), s.s2[i].imag()});
    }
    j["angles_deg"] = s.angles_deg;
    j["s1"] = s1;
    j["s2"] = s2;
  }
  std::cout << j.dump(2) << "\n";
}

// Amplitudes cost one series term per angle and order: refuse a request that
// would run for minutes (e.g. 1e6 angles at x = 1e4) before spending it.
constexpr double kMaxAmplitudeTerms = 1e9;  // a few seconds on one core

void require_affordable_amplitudes(double x, std::size_t angles) {
  if (!(x > 0 && x <= 1e6)) return;  // outside the domain: scatter() says so
  const double work = static_cast<double>(angles) * static_cast<double>(mie::wiscombe_terms(x));
  if (work > kMaxAmplitudeTerms)
    throw std::invalid_argument("mie: " + std::to_string(angles) + " angles x about " +
                                std::to_string(mie::wiscombe_terms(x)) + " series terms at x = " + io::shortest(x) +
                                " is more than the " + io::significant(kMaxAmplitudeTerms, 2) +
                                " amplitude terms this command computes; give --angles a coarser step");
}

void run(const MieArgs& a, const CLI::App& cmd) {
  const mie::Options options = make_options(a);
  if (cmd.count("--x") == 0) {
    // Batch mode: stdin -> CSV on stdout, bad lines on stderr, exit 1 if any.
    if (!a.angles.empty() || a.json) throw std::invalid_argument("mie: --angles and --json need --x");
    ErrorPrefixBuf prefix(std::cerr);
    std::ostream errors(&prefix);
    const std::size_t bad = mie::batch::run(std::cin, std::cout, errors, options);
    if (bad) exit_status() = 1;
    return;
  }
  const std::complex<double> m = mie::batch::parse_refractive_index(a.m);
  mie::Extras extras;
  if (!a.angles.empty()) extras.angles_deg = mie::batch::parse_angles(a.angles);
  require_affordable_amplitudes(a.x, extras.angles_deg.size());
  const mie::Scattering<double> s = mie::scatter(a.x, m, extras, options);
  if (a.json) print_json(a, m, s);
  else print_text(a, m, s);
}

}  // namespace

void register_mie(CLI::App& app) {
  auto args = std::make_shared<MieArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mie",
      "Lorenz-Mie efficiencies of a homogeneous sphere (Bohren & Huffman conventions, m = n + ik, k >= 0 "
      "absorbing). Without --x: batch mode, lines 'x m_re m_im' on stdin -> CSV on stdout.");
  cmd->add_option("--x", args->x, "size parameter 2*pi*r/lambda (> 0)");
  cmd->add_option("--m", args->m, "relative refractive index m = n + ik: 'n+ki', 'n,k' or 'n' (e.g. 1.5+0.1i, 1.5,0.1; default 1.33,0)");
  cmd->add_option("--angles", args->angles, "scattering angles in degrees for S1, S2: start:stop:step or a,b,c");
  cmd->add_flag("--json", args->json, "print JSON instead of text");
  cmd->add_option("--terms", args->terms, "term count: converged (default) or wiscombe")
      ->check(CLI::IsMember({"converged", "wiscombe"}));
  cmd->add_option("--working", args->working,
                  "working precision: auto (default: double, long double recurrences where double is not enough), double (fast, less accurate at large x), extended")
      ->check(CLI::IsMember({"auto", "double", "extended"}));
  cmd->callback([args, cmd]() { run(*args, *cmd); });
}

}  // namespace attenuvis::cli
