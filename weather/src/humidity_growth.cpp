// A component at a humidity by the humidity rule (humidity_growth.hpp).
#include "attenuvis/weather/humidity_growth.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/domains.hpp"

namespace attenuvis::weather {

double kappa_of_growth(double g, double rh) {
  const double a = rh / 100;
  return (g * g * g - 1) * (1 - a) / a;
}

double growth_of_kappa(double kappa, double rh) {
  const double a = rh / 100;
  return std::cbrt(1 + kappa * a / (1 - a));
}

std::complex<double> AerosolPopulation::index_at(double wavelength_m) const {
  ATTENUVIS_CHECK(lower != nullptr);
  const std::complex<double> m = lower->index.at(wavelength_m);
  if (upper_share == 0) return m;
  return m + upper_share * (upper->index.at(wavelength_m) - m);
}

std::string AerosolPopulation::describe() const {
  std::string out = to_string(component) + " at " + io::shortest(rh_percent) + " % RH";
  if (!info(component).hygroscopic) return out;
  out += " (g = " + io::significant(growth_factor, 4);
  if (weight != 1) out += ", " + io::significant(100 * weight, 4) + " % of its particles";
  return out + ")";
}

std::string AerosolPopulation::key() const {
  // The state alone (not the weight): per particle, the optics depend on nothing else.
  return to_string(component) + "@" + io::shortest(rh_percent) + "/" + io::shortest(r_mod_m) + "/" +
         io::shortest(upper_share);
}

namespace {

double water_fraction(double g) { return 1 - 1 / (g * g * g); }

AerosolPopulation tabulated(const OpacComponentData& d, std::size_t i, double weight) {
  const OpacState& s = d.states[i];
  AerosolPopulation p;
  p.component = d.component;
  p.weight = weight;
  p.rh_percent = s.rh_percent;
  p.growth_factor = s.r_mod_m / d.states.front().r_mod_m;
  p.r_mod_m = s.r_mod_m;
  p.sigma_g = s.sigma_g;
  p.r_min_m = s.r_min_m;
  p.r_max_m = s.r_max_m;
  p.density_kg_m3 = s.density_kg_m3;
  p.lower = &s;
  return p;
}

// kappa-Koehler between states i and i + 1 (humidity_growth.hpp).
AerosolPopulation kappa_grown(const OpacComponentData& d, std::size_t i, double rh) {
  const OpacState& lo = d.states[i];
  const OpacState& hi = d.states[i + 1];
  const double dry = d.states.front().r_mod_m;
  const double g_lo = lo.r_mod_m / dry, g_hi = hi.r_mod_m / dry;
  const double k_hi = kappa_of_growth(g_hi, hi.rh_percent);
  const double k_lo = lo.rh_percent > 0 ? kappa_of_growth(g_lo, lo.rh_percent) : k_hi;
  const double kappa = k_lo + (k_hi - k_lo) * (rh - lo.rh_percent) / (hi.rh_percent - lo.rh_percent);
  const double g = growth_of_kappa(kappa, rh);
  // Between the neighbours in ln g (the cut-offs) and in the water fraction (index, density).
  const double s = std::log(g / g_lo) / std::log(g_hi / g_lo);
  const double t = (water_fraction(g) - water_fraction(g_lo)) / (water_fraction(g_hi) - water_fraction(g_lo));
  ATTENUVIS_CHECK(s >= -1e-12 && s <= 1 + 1e-12 && t >= -1e-12 && t <= 1 + 1e-12);
  AerosolPopulation p = tabulated(d, i, 1.0);
  p.rh_percent = rh;
  p.growth_factor = g;
  p.r_mod_m = dry * g;
  p.r_min_m = lo.r_min_m * std::pow(hi.r_min_m / lo.r_min_m, s);
  p.r_max_m = lo.r_max_m * std::pow(hi.r_max_m / lo.r_max_m, s);
  p.density_kg_m3 = lo.density_kg_m3 + t * (hi.density_kg_m3 - lo.density_kg_m3);
  p.upper = &hi;
  p.upper_share = t;
  return p;
}

}  // namespace

std::vector<AerosolPopulation> component_populations(AerosolComponent c, double rh, HumidityRule rule) {
  require_in(domain::relative_humidity, rh);
  const OpacComponentData& d = opac_component(c);
  if (d.states.size() == 1) return {tabulated(d, 0, 1.0)};
  std::size_t i = 0;
  while (i + 1 < d.states.size() && d.states[i + 1].rh_percent <= rh) ++i;
  if (d.states[i].rh_percent == rh) return {tabulated(d, i, 1.0)};
  ATTENUVIS_CHECK(i + 1 < d.states.size());  // rh <= 99, the last tabulated humidity
  const double lo = d.states[i].rh_percent, hi = d.states[i + 1].rh_percent;
  switch (rule) {
    case HumidityRule::kappa: return {kappa_grown(d, i, rh)};
    case HumidityRule::linear: {
      const double t = (rh - lo) / (hi - lo);
      return {tabulated(d, i, 1 - t), tabulated(d, i + 1, t)};
    }
    case HumidityRule::nearest: return {tabulated(d, hi - rh < rh - lo ? i + 1 : i, 1.0)};
  }
  throw std::invalid_argument("unknown humidity rule");
}

KappaFit single_kappa_fit(AerosolComponent c) {
  const OpacComponentData& d = opac_component(c);
  if (d.states.size() < 2) return {};
  // g^3 - 1 = kappa x with x = a/(1 - a): least squares through the origin.
  double sxy = 0, sxx = 0;
  const double dry = d.states.front().r_mod_m;
  for (std::size_t i = 1; i < d.states.size(); ++i) {
    const double a = d.states[i].rh_percent / 100, x = a / (1 - a);
    const double g = d.states[i].r_mod_m / dry;
    sxy += x * (g * g * g - 1);
    sxx += x * x;
  }
  KappaFit fit{sxy / sxx, 0};
  for (std::size_t i = 1; i < d.states.size(); ++i) {
    const double g = d.states[i].r_mod_m / dry;
    fit.max_growth_error =
        std::max(fit.max_growth_error, std::abs(growth_of_kappa(fit.kappa, d.states[i].rh_percent) / g - 1));
  }
  return fit;
}

}  // namespace attenuvis::weather
