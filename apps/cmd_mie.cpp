// `attenuvis mie`: Lorenz–Mie efficiencies of one sphere (--x and --m, or
// --radius, --wavelength and --medium-index), with its amplitudes, scattering
// matrix and moments on request, or a batch read from stdin (no sphere given).  Parsing and formatting of the batch live in
// attenuvis/mie/batch.hpp; this file only maps options to library calls.
#include <cmath>
#include <iostream>
#include <memory>
#include <streambuf>
#include <string>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie.hpp"
#include "attenuvis/mie/batch.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/weather/units.hpp"
#include "commands.hpp"
#include "mie_output.hpp"
#include "weather_options.hpp"

namespace attenuvis::cli {
namespace {

// Writes to `target` with "attenuvis: error: " before each line, so that the
// batch's "line N: why" messages read like every other error of the program
// (apps/main.cpp).  Whole lines at a time: std::cerr is unbuffered, and one
// character per put() was one system call per character.
class ErrorPrefixBuf : public std::streambuf {
 public:
  explicit ErrorPrefixBuf(std::ostream& target) : target_(target) {}
  ~ErrorPrefixBuf() override { sync(); }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    xsputn(&ch, 1);
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) {
      if (line_.empty()) line_ = "attenuvis: error: ";
      line_ += s[i];
      if (s[i] == '\n') emit();
    }
    return n;
  }
  int sync() override {
    if (!line_.empty()) emit();
    target_.flush();
    return 0;
  }

 private:
  void emit() {
    target_.write(line_.data(), static_cast<std::streamsize>(line_.size()));
    line_.clear();
  }
  std::ostream& target_;
  std::string line_;  // the current line, with its prefix
};

struct MieArgs {
  double x = 0;
  std::string radius, wavelength;  // with units, e.g. 5um and 550nm
  std::string layers, x_layers;    // "r:m,r:m" (radii, um unless a unit is given) or "x:m,x:m"
  double medium_index = 1.0;
  std::string m = "1.33,0";
  std::string angles, phase;
  std::size_t moments = 0;
  bool polarised = false;
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

// Amplitudes cost one series term per angle and order, and moments O(N^2)
// term products: refuse a request that would run for minutes (e.g. 1e6 angles
// at x = 1e4) before spending it.
constexpr double kMaxSeriesWork = 1e9;  // a few seconds on one core

void require_affordable(double x, double work_per_term, const std::string& what, const std::string& advice) {
  if (!(x > 0 && x <= 1e6)) return;  // outside the domain: scatter() says so
  const double terms = static_cast<double>(mie::wiscombe_terms(x));
  const double work = work_per_term * terms;
  if (work > kMaxSeriesWork)
    throw std::invalid_argument("mie: " + what + " at x = " + io::shortest(x) + " (about " + io::shortest(terms) +
                                " series terms) is more than the " + io::significant(kMaxSeriesWork, 2) +
                                " term evaluations this command computes; " + advice);
}

// A layer's radius in --layers: micrometres, or a number with its unit.
double layer_radius(const std::string& text) {
  const bool has_unit = !text.empty() && std::isalpha(static_cast<unsigned char>(text.back()));
  return has_unit ? weather::parse_length(text, "--layers radius") : weather::parse_length(text + "um", "--layers radius");
}

// A layered sphere from --layers (with --wavelength) or --x-layers.
MieEcho resolve_layers(const MieArgs& a, const CLI::App& cmd) {
  for (const char* o : {"--x", "--radius", "--m"})
    if (cmd.count(o)) throw std::invalid_argument(std::string("mie: ") + o + " does not go with --layers/--x-layers");
  const bool by_radius = cmd.count("--layers") > 0;
  if (by_radius && cmd.count("--x-layers")) throw std::invalid_argument("mie: give --layers or --x-layers, not both");
  if (by_radius != (cmd.count("--wavelength") > 0))
    throw std::invalid_argument(by_radius ? "mie: --layers needs --wavelength" : "mie: --wavelength goes with --layers");
  if (!by_radius && cmd.count("--medium-index")) throw std::invalid_argument("mie: --medium-index goes with --layers");
  if (!(std::isfinite(a.medium_index) && a.medium_index >= 1e-3 && a.medium_index <= 1e3))
    throw std::invalid_argument("mie: --medium-index must be a real index in [0.001, 1000], got " +
                                io::shortest(a.medium_index));
  const char* option = by_radius ? "--layers" : "--x-layers";
  const std::vector<mie::batch::LayerText> layers = mie::batch::parse_layers(by_radius ? a.layers : a.x_layers, option);
  MieEcho e;
  e.term_rule = a.terms;
  e.conducting_core = !layers.front().m;
  const double lambda = by_radius ? weather::parse_wavelength(a.wavelength) : 0;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    double x = 0;
    if (by_radius) {
      x = 2 * M_PI * a.medium_index * layer_radius(layers[l].size) / lambda;
    } else {
      try {
        x = io::parse_double(layers[l].size, "size parameter");
      } catch (const std::exception& err) {
        throw std::invalid_argument(std::string("mie: --x-layers layer ") + std::to_string(l) + ": " + err.what());
      }
    }
    e.layer_x.push_back(x);
    if (layers[l].m) e.layer_m.push_back(*layers[l].m / a.medium_index);
  }
  e.x = e.layer_x.back();
  e.m = e.layer_m.empty() ? std::complex<double>(0) : e.layer_m.back();
  if (by_radius)
    e.size_text = "radii and wavelength " + a.wavelength + " in vacuum, medium index " + io::shortest(a.medium_index);
  return e;
}

// The sphere as the user gave it: --x and --m, or --radius and --wavelength
// (x = 2 pi n_medium r / lambda, m relative = m / n_medium), or its layers.
MieEcho resolve_sphere(const MieArgs& a, const CLI::App& cmd) {
  if (cmd.count("--layers") || cmd.count("--x-layers")) return resolve_layers(a, cmd);
  MieEcho e;
  e.term_rule = a.terms;
  const std::complex<double> m = mie::batch::parse_refractive_index(a.m);
  const bool by_size = cmd.count("--radius") || cmd.count("--wavelength");
  if (!by_size) {
    if (cmd.count("--medium-index")) throw std::invalid_argument("mie: --medium-index needs --radius and --wavelength");
    e.x = a.x;
    e.m = m;
    return e;
  }
  if (cmd.count("--x")) throw std::invalid_argument("mie: give --x, or --radius with --wavelength, not both");
  if (!cmd.count("--radius") || !cmd.count("--wavelength"))
    throw std::invalid_argument("mie: --radius and --wavelength go together (or give --x)");
  if (!(std::isfinite(a.medium_index) && a.medium_index >= 1e-3 && a.medium_index <= 1e3))
    throw std::invalid_argument("mie: --medium-index must be a real index in [0.001, 1000], got " +
                                io::shortest(a.medium_index));
  const double r = weather::parse_length(a.radius, "--radius");
  const double lambda = weather::parse_wavelength(a.wavelength);
  e.x = 2 * M_PI * a.medium_index * r / lambda;
  e.m = m / a.medium_index;
  e.size_text = "radius " + a.radius + ", wavelength " + a.wavelength + " in vacuum, medium index " +
                io::shortest(a.medium_index);
  return e;
}

// The parser's own limit: the cost check below refuses what is too dear.
constexpr std::size_t kMaxMieAngles = 1000000;

MieResult compute(const MieArgs& a, const CLI::App& cmd, const MieEcho& e) {
  mie::Extras extras;
  std::vector<double> matrix_angles;
  if (!a.angles.empty()) extras.angles_deg = angle_list("--angles", a.angles, kMaxMieAngles);
  if (!a.phase.empty()) matrix_angles = angle_list("--phase", a.phase, kMaxMieAngles);
  require_affordable(e.x, static_cast<double>(extras.angles_deg.size() + matrix_angles.size()),
                     "amplitudes at " + std::to_string(extras.angles_deg.size() + matrix_angles.size()) + " angles",
                     "give --angles/--phase a coarser step");
  const bool want_moments = cmd.count("--moments") > 0;
  if (a.polarised && !want_moments) throw std::invalid_argument("mie: --polarised needs --moments L");
  if (want_moments) {
    extras.coefficients = true;
    // 2N+1 quadrature nodes x N terms (legendre_moments.hpp), six products each with --polarised.
    const double per_term = 2.0 * static_cast<double>(mie::wiscombe_terms(e.x)) * (a.polarised ? 3.0 : 1.0);
    require_affordable(e.x, per_term, "Legendre moments", "they cost O(N^2); use a smaller x");
  }
  const mie::Options options = make_options(a);
  MieResult r;
  if (e.layer_x.empty()) {
    r.s = mie::scatter(e.x, e.m, extras, options);
    if (!matrix_angles.empty()) r.matrix = mie::scattering_matrix(e.x, e.m, matrix_angles);
  } else {
    const auto layered = [&](const mie::Extras& ex) {
      return e.conducting_core ? mie::layered_scatter(mie::PerfectConductor{}, e.layer_x, e.layer_m, ex, options)
                               : mie::layered_scatter(e.layer_x, e.layer_m, ex, options);
    };
    r.s = layered(extras);
    if (!matrix_angles.empty()) {
      mie::Extras at_matrix;
      at_matrix.angles_deg = matrix_angles;
      r.matrix = mie::scattering_matrix(e.x, layered(at_matrix));
    }
  }
  if (want_moments) {
    r.moments = mie::phase_function_moments(r.s, a.moments);
    if (a.polarised) r.expansion = mie::scattering_matrix_expansion(r.s, a.moments);
  }
  return r;
}

void run(const MieArgs& a, const CLI::App& cmd) {
  const bool one_sphere = cmd.count("--x") || cmd.count("--radius") || cmd.count("--wavelength") ||
                          cmd.count("--layers") || cmd.count("--x-layers");
  if (!one_sphere) {
    // Batch mode: stdin -> CSV on stdout, bad lines on stderr, exit 1 if any.
    for (const char* o : {"--angles", "--phase", "--moments", "--polarised", "--json", "--medium-index"})
      if (cmd.count(o)) throw std::invalid_argument(std::string("mie: ") + o + " needs one sphere (--x, or --radius and --wavelength)");
    ErrorPrefixBuf prefix(std::cerr);
    std::ostream errors(&prefix);
    const std::size_t bad = mie::batch::run(std::cin, std::cout, errors, make_options(a));
    if (bad) exit_status() = 1;
    return;
  }
  const MieEcho echo = resolve_sphere(a, cmd);
  const MieResult r = compute(a, cmd, echo);
  if (a.json) print_mie_json(echo, r);
  else print_mie_text(echo, r);
}

}  // namespace

void register_mie(CLI::App& app) {
  auto args = std::make_shared<MieArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mie",
      "Lorenz-Mie efficiencies, amplitudes and moments of homogeneous or layered spheres");
  cmd->add_option("--x", args->x, "size parameter 2*pi*r/lambda, in [1e-8, 1e6]");
  cmd->add_option("--radius", args->radius, "sphere radius with unit (nm, um, mm, m), e.g. 5um; with --wavelength instead of --x");
  cmd->add_option("--wavelength", args->wavelength, "vacuum wavelength with unit, e.g. 550nm; with --radius");
  cmd->add_option("--medium-index", args->medium_index,
                  "real refractive index of the medium (default 1): x = 2 pi n r / lambda, m relative = m / n");
  cmd->add_option("--layers", args->layers,
                  "a layered sphere, core first: outer radius:index of each layer, e.g. 0.5:1.75+0.44i,1.0:1.43+1e-8i "
                  "(radii in um unless a unit is given; index n+ki, or pec for a perfectly conducting core); with "
                  "--wavelength (and --medium-index)");
  cmd->add_option("--x-layers", args->x_layers,
                  "a layered sphere by size parameters, core first: x:index of each layer's outer radius, e.g. "
                  "5.71:1.75+0.44i,11.42:1.43+1e-8i");
  cmd->add_option("--m", args->m, "relative refractive index m = n + ik: 'n+ki', 'n,k' or 'n' (e.g. 1.5+0.1i, 1.5,0.1; default 1.33,0)");
  cmd->add_option("--angles", args->angles, "scattering angles in degrees for S1, S2: start:stop:step or a,b,c");
  cmd->add_option("--phase", args->phase,
                  "angles (degrees, as --angles) for the scattering matrix S11, S12, S33, S34 and the phase function p "
                  "(integral of p over 4 pi sr = 4 pi)");
  cmd->add_option("--moments", args->moments,
                  "Legendre moments chi_0..chi_L of the phase function (chi_0 = 1, chi_1 = g; zero above 2N)");
  cmd->add_flag("--polarised", args->polarised, "with --moments: also alpha1..alpha4, beta1, beta2 of the whole matrix");
  cmd->add_flag("--json", args->json, "print JSON instead of text");
  cmd->add_option("--terms", args->terms, "term count: converged (default) or wiscombe")
      ->check(CLI::IsMember({"converged", "wiscombe"}));
  cmd->add_option("--working", args->working,
                  "working precision: auto (default: double, long double recurrences where double is not enough), double (fast, less accurate at large x), extended")
      ->check(CLI::IsMember({"auto", "double", "extended"}));
  cmd->callback([args, cmd]() { run(*args, *cmd); });
}

}  // namespace attenuvis::cli
