// Size distributions: densities, exact (tail) moments, presets, normalisation.
#include "attenuvis/weather/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include "attenuvis/weather/detail/analytic_density.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/domains.hpp"
#include "registry_rows.hpp"

namespace attenuvis::weather {
namespace {

template <class... Ts>
struct Overloaded : Ts... { using Ts::operator()...; };
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

constexpr double kPi = boost::math::constants::pi<double>();

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Modified gamma: M_p = (a/gamma) b^-s Gamma(s), s = (alpha + p + 1)/gamma.
double shape_s(const ModifiedGamma& g, double p) {
  double s = (g.alpha + p + 1) / g.gamma;
  if (!(s > 0))
    throw std::invalid_argument("moment of order " + std::to_string(p) +
                                " of the modified gamma distribution diverges at r -> 0 (alpha + p + 1 <= 0)");
  return s;
}
double log_moment(const ModifiedGamma& g, double p) {
  double s = shape_s(g, p);
  return (p + 1) * std::log(g.r0) + std::log(g.a / g.gamma) - s * std::log(g.b) + boost::math::lgamma(s);
}

// Standard normal lower-tail probability and its inverse.
double normal_cdf(double z) { return 0.5 * boost::math::erfc(-z / std::sqrt(2.0)); }
double normal_quantile(double q) { return -std::sqrt(2.0) * boost::math::erfc_inv(2 * q); }

// Exact integral of r^p (n0 + slope (r - r0)) over one straight segment.  The
// integrand is a polynomial for integer p, so 8-point Gauss-Legendre is exact
// up to p = 14; for fractional p it is accurate to ~1e-15 on any segment
// whose width is below its radius, which is what files contain.
double segment_moment(const TabulatedSegment& s, double p) {
  auto f = [&](double r) {
    double t = (s.r1 > s.r0) ? (r - s.r0) / (s.r1 - s.r0) : 0.0;
    return std::pow(r, p) * (s.n0 + (s.n1 - s.n0) * t);
  };
  return boost::math::quadrature::gauss<double, 8>::integrate(f, s.r0, s.r1);
}

}  // namespace

SizeDistribution SizeDistribution::modified_gamma_um(double a, double alpha, double b, double gamma) {
  require(a > 0 && b > 0 && gamma > 0 && std::isfinite(alpha),
          "modified gamma distribution needs a > 0, b > 0, gamma > 0");
  // n_SI(r) = 1e6 (cm^-3 -> m^-3) * 1e6 (um^-1 -> m^-1) * a t^alpha exp(-b t^gamma), t = r / 1 um.
  ModifiedGamma g{a * 1e12, alpha, b, gamma, 1e-6};
  std::ostringstream name;
  name << "modified gamma a=" << a << " alpha=" << alpha << " b=" << b << " gamma=" << gamma
       << " (r in um, n in cm^-3 um^-1)";
  return SizeDistribution(g, name.str());
}

SizeDistribution SizeDistribution::gamma(double number_per_m3, double alpha, double mode_radius_m) {
  require(number_per_m3 > 0 && alpha > 0 && mode_radius_m > 0,
          "gamma distribution needs N > 0, alpha > 0 and a mode radius > 0");
  // n = a t^alpha e^{-alpha t}, t = r / r_mode (mode of t^alpha e^{-alpha t} is t = 1);
  // N = r_mode a Gamma(alpha+1) / alpha^(alpha+1).
  double b = alpha;
  double a = number_per_m3 / mode_radius_m * std::exp((alpha + 1) * std::log(b) - boost::math::lgamma(alpha + 1));
  std::ostringstream name;
  name << "gamma N=" << number_per_m3 << " m^-3 alpha=" << alpha << " r_mode=" << mode_radius_m << " m";
  return SizeDistribution(ModifiedGamma{a, alpha, b, 1.0, mode_radius_m}, name.str());
}

SizeDistribution SizeDistribution::log_normal(double number_per_m3, double median_radius_m, double sigma_g) {
  require(number_per_m3 > 0 && median_radius_m > 0 && sigma_g > 1,
          "log-normal distribution needs N > 0, median radius > 0 and sigma_g > 1");
  std::ostringstream name;
  name << "log-normal N=" << number_per_m3 << " m^-3 r_g=" << median_radius_m << " m sigma_g=" << sigma_g;
  return SizeDistribution(LogNormal{number_per_m3, median_radius_m, sigma_g}, name.str());
}

SizeDistribution SizeDistribution::exponential_diameter(double n0, double lambda) {
  require(n0 > 0 && lambda > 0, "exponential distribution needs N0 > 0 and Lambda > 0");
  // N(D) dD with D = 2r: n(r) = 2 N0 exp(-2 Lambda r); N0 m^-3 mm^-1 = 1e3 m^-4; Lambda mm^-1 = 1e3 m^-1.
  std::ostringstream name;
  name << "exponential N0=" << n0 << " m^-3 mm^-1 Lambda=" << lambda << " mm^-1 (in diameter)";
  return SizeDistribution(ModifiedGamma{2 * n0 * 1e3, 0.0, 2 * lambda * 1e3, 1.0, 1.0}, name.str());
}

SizeDistribution SizeDistribution::marshall_palmer(double rate) {
  require(rate > 0, "Marshall-Palmer rain needs a rain rate > 0 mm/h");
  auto d = exponential_diameter(8000.0, 4.1 * std::pow(rate, -0.21));
  d.name_ = "Marshall-Palmer rain R=" + std::to_string(rate) + " mm/h (N0=8000 m^-3 mm^-1, Lambda=4.1 R^-0.21 mm^-1)";
  return d;
}

SizeDistribution SizeDistribution::gunn_marshall(double rate) {
  require(rate > 0, "Gunn-Marshall snow needs a precipitation rate > 0 mm/h");
  auto d = exponential_diameter(3800.0 * std::pow(rate, -0.87), 2.55 * std::pow(rate, -0.48));
  d.name_ = "Gunn-Marshall snow R=" + std::to_string(rate) +
            " mm/h (N0=3800 R^-0.87 m^-3 mm^-1, Lambda=2.55 R^-0.48 mm^-1, melted diameter)";
  return d;
}

SizeDistribution SizeDistribution::power_law(double c, double nu, double r_min, double r_max) {
  require(c > 0 && r_min > 0 && r_max > r_min, "power law needs C > 0 and 0 < r_min < r_max");
  std::ostringstream name;
  name << "power law C=" << c << " nu=" << nu << " on [" << r_min << ", " << r_max << "] m";
  return SizeDistribution(PowerLaw{c, nu, r_min, r_max}, name.str());
}

SizeDistribution SizeDistribution::tabulated(std::vector<TabulatedSegment> segments, std::string source) {
  require(!segments.empty(), "tabulated distribution has no segments");
  std::string name = "tabulated (" + source + ")";
  return SizeDistribution(Tabulated{std::move(segments), std::move(source)}, name);
}

double SizeDistribution::density(double r) const {
  if (!(r > 0)) return 0;
  return std::visit(
      Overloaded{
          [&](const ModifiedGamma& g) { return detail::modified_gamma_density(g, r); },
          [&](const LogNormal& l) { return detail::log_normal_density(l, r); },
          [&](const PowerLaw& p) { return (r < p.r_min_m || r > p.r_max_m) ? 0.0 : p.c * std::pow(r, -p.nu); },
          [&](const Tabulated& t) {
            for (const auto& s : t.segments)
              if (r >= s.r0 && r <= s.r1)
                return s.r1 > s.r0 ? s.n0 + (s.n1 - s.n0) * (r - s.r0) / (s.r1 - s.r0) : s.n0;
            return 0.0;
          }},
      form_);
}

double SizeDistribution::moment(double p) const {
  return std::visit(
      Overloaded{[&](const ModifiedGamma& g) { return std::exp(log_moment(g, p)); },
                 [&](const LogNormal& l) {
                   double s = std::log(l.sigma_g);
                   return l.number_per_m3 * std::pow(l.median_radius_m, p) * std::exp(0.5 * p * p * s * s);
                 },
                 [&](const PowerLaw& pl) {
                   double q = p - pl.nu + 1;
                   if (std::abs(q) < 1e-12) return pl.c * std::log(pl.r_max_m / pl.r_min_m);
                   return pl.c * (std::pow(pl.r_max_m, q) - std::pow(pl.r_min_m, q)) / q;
                 },
                 [&](const Tabulated& t) {
                   double sum = 0;
                   for (const auto& s : t.segments) sum += segment_moment(s, p);
                   return sum;
                 }},
      form_);
}

Support SizeDistribution::support(double p, double tail_fraction) const {
  require(tail_fraction > 0 && tail_fraction < 1, "tail fraction must lie in (0, 1)");
  Support out;
  out.total_moment = moment(p);
  std::visit(
      Overloaded{
          [&](const ModifiedGamma& g) {
            // b r^gamma is Gamma(s)-distributed under the weight r^p n(r).
            double s = shape_s(g, p);
            double t_lo = boost::math::gamma_p_inv(s, 0.5 * tail_fraction);
            double t_hi = boost::math::gamma_q_inv(s, 0.5 * tail_fraction);
            double t_lo_r = std::pow(t_lo / g.b, 1 / g.gamma), t_hi_r = std::pow(t_hi / g.b, 1 / g.gamma);
            t_lo_r = std::max(t_lo_r, 1e-6 * t_hi_r);  // below this the weight is negligible; counted exactly below
            out.breakpoints_m = {t_lo_r * g.r0, t_hi_r * g.r0};
            out.omitted_moment = out.total_moment * (boost::math::gamma_p(s, g.b * std::pow(t_lo_r, g.gamma)) +
                                                     boost::math::gamma_q(s, g.b * std::pow(t_hi_r, g.gamma)));
          },
          [&](const LogNormal& l) {
            double s = std::log(l.sigma_g), mu = std::log(l.median_radius_m) + p * s * s;
            double z = -normal_quantile(0.5 * tail_fraction);
            out.breakpoints_m = {std::exp(mu - z * s), std::exp(mu + z * s)};
            out.omitted_moment = out.total_moment * 2 * normal_cdf(-z);
          },
          [&](const PowerLaw& pl) { out.breakpoints_m = {pl.r_min_m, pl.r_max_m}; },
          [&](const Tabulated& t) {
            for (const auto& seg : t.segments) {
              out.breakpoints_m.push_back(seg.r0);
              out.breakpoints_m.push_back(seg.r1);
            }
            std::sort(out.breakpoints_m.begin(), out.breakpoints_m.end());
            out.breakpoints_m.erase(std::unique(out.breakpoints_m.begin(), out.breakpoints_m.end()),
                                    out.breakpoints_m.end());
          }},
      form_);
  return out;
}

SizeDistribution SizeDistribution::scaled(double f) const {
  Form form = std::visit(
      Overloaded{[&](ModifiedGamma g) -> Form { g.a *= f; return g; },
                 [&](LogNormal l) -> Form { l.number_per_m3 *= f; return l; },
                 [&](PowerLaw p) -> Form { p.c *= f; return p; },
                 [&](Tabulated t) -> Form {
                   for (auto& s : t.segments) { s.n0 *= f; s.n1 *= f; }
                   return t;
                 }},
      form_);
  std::ostringstream name;
  name << name_ << " x " << f;
  return SizeDistribution(std::move(form), name.str());
}

std::string SizeDistribution::describe() const { return name_; }

const std::vector<FogPresetInfo>& fog_presets() {
  // The seed paper's Table "Attenuation coefficient parameters for Fog" (from ITU-R P.1817-1).
  static const std::string source =
      "ITU-R P.1817-1, as tabulated in the seed paper (Schwartz, Vinnikov, Federici, SimAUD 2021), Table "
      "\"Attenuation coefficient parameters for Fog\"";
  static const std::vector<FogPresetInfo> presets = [] {
    std::vector<FogPresetInfo> p = {
        {FogPreset::advection, "advection", "heavy advection fog", 0.027, 3, 0.3, source},
        {FogPreset::radiation, "radiation", "moderate radiation fog", 607.5, 6, 3, source},
    };
    detail::check_enum_order(p, &FogPresetInfo::id);
    return p;
  }();
  return presets;
}

const FogPresetInfo& info(FogPreset p) { return detail::row_of(fog_presets(), p); }

const FogPresetInfo* find_fog_preset(const std::string& name) { return detail::find_by_name(fog_presets(), name); }

std::string to_string(FogPreset p) { return info(p).name; }

namespace {

// The presets set by a rate: the name up to and including ':', the rate's
// range and the distribution of that rate.
struct RatePreset {
  const char* prefix;  // "marshall-palmer:"
  const char* help;
  const char* citation;
  const Domain& rate;
  SizeDistribution (*at)(double rate_mm_h);
};
const RatePreset kRatePresets[] = {
    {"marshall-palmer:", "rain, R mm/h", "J. S. Marshall and W. McK. Palmer, J. Meteor. 5, 165 (1948)",
     domain::rain_rate, &SizeDistribution::marshall_palmer},
    {"gunn-marshall:", "snow, R mm/h melted", "K. L. S. Gunn and J. S. Marshall, J. Meteor. 15, 452 (1958)",
     domain::snow_rate, &SizeDistribution::gunn_marshall},
};

const RatePreset* rate_preset(const std::string& name) {
  for (const auto& p : kRatePresets)
    if (name.rfind(p.prefix, 0) == 0) return &p;
  return nullptr;
}

// "advection (heavy advection fog), ..., gunn-marshall:R (snow, R mm/h melted)".
std::string preset_list() {
  std::string out;
  for (const auto& p : distribution_presets()) out += (out.empty() ? "" : ", ") + p.name + " (" + p.help + ")";
  return out;
}

}  // namespace

const std::vector<DistributionPresetInfo>& distribution_presets() {
  static const std::vector<DistributionPresetInfo> presets = [] {
    std::vector<DistributionPresetInfo> out;
    for (const auto& p : fog_presets()) out.push_back({p.name, p.help, p.citation});
    for (const auto& p : kRatePresets) out.push_back({std::string(p.prefix) + "R", p.help, p.citation});
    return out;
  }();
  return presets;
}

bool is_preset_distribution(const std::string& name) {
  return find_fog_preset(name) != nullptr || rate_preset(name) != nullptr;
}

SizeDistribution preset_distribution(const std::string& name) {
  if (const FogPresetInfo* fog = find_fog_preset(name)) {
    auto d = SizeDistribution::modified_gamma_um(fog->a, fog->alpha, fog->b);
    return SizeDistribution(d.form(), fog->help + " (P.1817-1: alpha=" + io::shortest(fog->alpha) +
                                          ", a=" + io::shortest(fog->a) + ", b=" + io::shortest(fog->b) +
                                          "; r um, n cm^-3 um^-1)");
  }
  if (const RatePreset* p = rate_preset(name)) {
    const std::size_t prefix = std::string(p->prefix).size();
    double rate = 0;
    try {
      rate = read_in(p->rate, name.substr(prefix));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("size distribution preset " + quote_text(name) + ": " + e.what());
    }
    return p->at(rate);
  }
  throw std::invalid_argument("unknown size distribution preset '" + name + "'; presets: " + preset_list());
}

Moments moments(const SizeDistribution& d, double rho) {
  Moments m;
  double m0 = d.moment(0), m1 = d.moment(1), m2 = d.moment(2), m3 = d.moment(3);
  m.number_per_m3 = m0;
  m.water_content_kg_m3 = rho * 4.0 / 3.0 * kPi * m3;
  m.effective_radius_m = m3 / m2;
  m.mean_radius_m = m1 / m0;
  m.mode_radius_m = std::visit(
      Overloaded{[&](const ModifiedGamma& g) {
                   return g.alpha > 0 ? g.r0 * std::pow(g.alpha / (g.b * g.gamma), 1 / g.gamma) : 0.0;
                 },
                 [&](const LogNormal& l) {
                   double s = std::log(l.sigma_g);
                   return l.median_radius_m * std::exp(-s * s);
                 },
                 [&](const PowerLaw& p) { return p.nu > 0 ? p.r_min_m : p.r_max_m; },
                 [&](const Tabulated& t) {
                   // The largest density; on a flat segment (a bin, or a plateau
                   // between two equal points) the mode is its middle.
                   double best = -1, at = 0;
                   for (const auto& s : t.segments) {
                     const bool flat = s.n0 == s.n1;
                     const double middle = 0.5 * (s.r0 + s.r1);
                     if (s.n0 > best) { best = s.n0; at = flat ? middle : s.r0; }
                     else if (flat && s.n0 == best && at == s.r0) at = middle;  // the peak continues as a plateau
                     if (s.n1 > best) { best = s.n1; at = s.r1; }
                   }
                   return at;
                 }},
      d.form());
  return m;
}

SizeDistribution normalised_to_number(const SizeDistribution& d, double number_per_m3) {
  require(number_per_m3 > 0, "target number density must be > 0");
  return d.scaled(number_per_m3 / d.moment(0));
}

SizeDistribution normalised_to_water_content(const SizeDistribution& d, double kg_per_m3, double rho) {
  require(kg_per_m3 > 0 && rho > 0, "target water content and bulk density must be > 0");
  return d.scaled(kg_per_m3 / (rho * 4.0 / 3.0 * kPi * d.moment(3)));
}

}  // namespace attenuvis::weather
