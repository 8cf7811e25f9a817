// sigma for every kind of condition: a visit over the typed condition.
#include "attenuvis/weather/sigma.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/aerosol_optics.hpp"
#include "attenuvis/weather/coated_optics.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/distribution_file.hpp"
#include "attenuvis/weather/index_file.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/segmented_contour.hpp"
#include "attenuvis/weather/visibility.hpp"
#include "real_axis_settings.hpp"

namespace attenuvis::weather {
namespace {

std::string g4(double v) { return io::significant(v, 4); }

bool is_rain(const MieCondition& c) { return std::holds_alternative<MarshallPalmerRain>(c.drops); }

// The real-axis quadrature of a Mie condition, over a distribution and index
// the caller already has (sigma() needs them for the contour first).
BulkOptics real_axis_optics(const MieCondition& c, double wavelength_m, const Settings& s, const SizeDistribution& d,
                            std::complex<double> m) {
  if (c.coating) return coated_bulk_optics(d, wavelength_m, m, *c.coating, detail::real_axis_settings(c, s));
  return integrate_bulk_optics(d, wavelength_m, mie_efficiency_batch(m), detail::real_axis_settings(c, s), m);
}

// What a Mie result depends on: the condition's value, the wavelength and
// the settings that enter the integral.  Conditions read from a file have no
// key (the file may change between calls).
using MieKey = std::tuple<std::size_t, double, std::size_t, std::size_t, double, double, std::string, std::size_t,
                          double, double, double, std::string, double, double, double, double, std::size_t>;
std::optional<MieKey> cache_key(const MieCondition& c, double wavelength_m, const Settings& s) {
  // Files may change between calls; parametric drops are keyed by no preset
  // (their sigma comes from the contour rule in milliseconds).
  if (std::holds_alternative<DistributionFile>(c.drops) || std::holds_alternative<ParametricDrops>(c.drops) ||
      std::holds_alternative<IndexFile>(c.index))
    return std::nullopt;
  const double rate = is_rain(c) ? std::get<MarshallPalmerRain>(c.drops).rate_mm_h : 0.0;
  const std::size_t preset = is_rain(c) ? 0 : static_cast<std::size_t>(std::get<FogPreset>(c.drops));
  double n = 0, k = 0;
  std::string table;
  if (const auto* m = std::get_if<ConstantIndex>(&c.index)) n = m->m.real(), k = m->m.imag();
  else if (const auto* t = std::get_if<WaterTable>(&c.index)) table = to_string(*t);
  else table = s.water_table;
  double scale = 0;
  if (const auto* v = std::get_if<NumberDensity>(&c.rescaling)) scale = v->per_cm3;
  if (const auto* v = std::get_if<LiquidWaterContent>(&c.rescaling)) scale = v->g_per_m3;
  // A coating: its volume fraction and index (-1: none).
  const double coat = c.coating ? c.coating->shell_volume_fraction : -1.0;
  const double shell_n = c.coating ? c.coating->shell_m.real() : 0.0, shell_k = c.coating ? c.coating->shell_m.imag() : 0.0;
  return MieKey{c.drops.index(), rate, preset, c.index.index(), n, k, table, c.rescaling.index(), scale,
                wavelength_m, s.rel_tolerance, s.water_table, s.rain_asymptotic_x, coat, shell_n, shell_k,
                s.max_evaluations};
}

// Mie integrals of near-lossless drops take seconds; a process asking for
// the same condition twice (an app, a table with repeated rows, a table cell
// that wants sigma and then the real-axis optics of the same drops) reuses
// the result.  Conditions without a key are computed every time.
template <class Value>
class MieMemo {
 public:
  template <class Compute>
  Value get(const std::optional<MieKey>& key, Compute compute) {
    if (key) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = values_.find(*key); it != values_.end()) return it->second;
    }
    Value v = compute();
    if (key) {
      std::lock_guard<std::mutex> lock(mutex_);
      values_.emplace(*key, v);
    }
    return v;
  }

 private:
  std::mutex mutex_;
  std::map<MieKey, Value> values_;
};

// sigma() falls back to the real axis where no contour applies (rain at
// optical wavelengths); a table cell then asks condition_bulk_optics() for
// the same integral: it is computed once.
BulkOptics bulk_optics_of(const MieCondition& c, double wavelength_m, const Settings& s, const SizeDistribution& d,
                          std::complex<double> m) {
  static MieMemo<BulkOptics> memo;
  return memo.get(cache_key(c, wavelength_m, s), [&] { return real_axis_optics(c, wavelength_m, s, d, m); });
}

Sigma mie_sigma(const MieCondition& c, double wavelength_m, const Settings& s) {
  Sigma out;
  out.convention = "n/a";
  std::string index_source;
  const std::complex<double> m = condition_refractive_index(c, wavelength_m, s, &index_source);
  const SizeDistribution d = condition_distribution(c);
  out.model = std::string(c.coating ? "layered-sphere Mie over core-shell particles, cores " : "Mie over ") + d.describe();
  std::ostringstream note;
  note.precision(3);
  // Analytic distributions within reach: integrate above the real axis,
  // where Q_ext's resonances are smooth (contour_extinction.hpp); else on
  // the real axis with the resonances as an error term (bulk_optics.hpp).
  // Tables and power laws with bounds: the same path, with Cauchy applied
  // piece by piece (segmented_contour.hpp).  Either declines beyond x = 5000
  // (rain at optical wavelengths), where the real axis with its large-x
  // expansion takes over.
  ContourSettings cs;
  cs.rel_tolerance = s.rel_tolerance;
  cs.cancel = s.cancel;
  SegmentedContourSettings ss;
  ss.rel_tolerance = s.rel_tolerance;
  ss.cancel = s.cancel;
  // Core-shell particles: the real axis (the contour needs the homogeneous
  // sphere's continuation; coated_optics.hpp).
  std::optional<ContourExtinction> ce;
  if (!c.coating) ce = contour_extinction(d, wavelength_m, m, cs);
  if (!ce && !c.coating) ce = segmented_contour_extinction(d, wavelength_m, m, ss);
  if (ce) {
    out.per_m = ce->extinction.value;
    out.error_per_m = ce->extinction.error();
    note << index_source << "; " << ce->method;
    out.error_terms = {{"quadrature", ce->extinction.quadrature_error},
                       {"tails", ce->extinction.tail_error},
                       {"rounding", ce->extinction.rounding_error}};
    if (ce->extinction.resonance_error > 0)
      out.error_terms.push_back({"near-axis resonances (bound)", ce->extinction.resonance_error});
  } else {
    const BulkOptics b = bulk_optics_of(c, wavelength_m, s, d, m);
    out.per_m = b.extinction.value;
    out.error_per_m = b.extinction.error();
    note << index_source << "; " << b.method;
    out.error_terms = {{"quadrature", b.extinction.quadrature_error},
                       {"tails", b.extinction.tail_error},
                       {"unresolved resonances", b.extinction.resonance_error}};
    if (b.extinction.asymptotic_error > 0) out.error_terms.push_back({"large-x expansion", b.extinction.asymptotic_error});
    out.shortfall = b.shortfall;
  }
  out.note = note.str();
  return out;
}

Sigma cached_mie_sigma(const MieCondition& c, double wavelength_m, const Settings& s) {
  static MieMemo<Sigma> memo;
  return memo.get(cache_key(c, wavelength_m, s), [&] { return mie_sigma(c, wavelength_m, s); });
}

std::string koschmieder_words(double visibility_m, const Settings& s) {
  return g4(visibility_m) + " m (Koschmieder, threshold " + g4(s.contrast_threshold) + ")";
}

std::string power_law_words(double published, const Settings& s) {
  return g4(published) + (s.convention == Convention::itu ? " dB/km" : " 1/km (seed reading)");
}

}  // namespace

QuadratureSettings detail::real_axis_settings(const MieCondition& c, const Settings& s) {
  QuadratureSettings q;
  q.rel_tolerance = s.rel_tolerance;
  q.max_evaluations = s.max_evaluations;
  q.cancel = s.cancel;
  if (is_rain(c)) q.asymptotic_x = s.rain_asymptotic_x;
  return q;
}

// The distribution of parametric drops; those without an amount of their own
// hold one particle per cm^3 (condition.hpp), rescaled by N= or lwc= below.
static SizeDistribution parametric_distribution(const ParametricDrops& p) {
  constexpr double kOnePerCm3 = 1e6;  // m^-3
  return std::visit(
      [&](const auto& f) -> SizeDistribution {
        using T = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<T, LogNormalDrops>)
          return SizeDistribution::log_normal(kOnePerCm3, f.median_radius_m, f.sigma_g);
        else if constexpr (std::is_same_v<T, GammaDrops>)
          return SizeDistribution::gamma(kOnePerCm3, f.alpha, f.mode_radius_m);
        else if constexpr (std::is_same_v<T, ModifiedGammaDrops>)
          return SizeDistribution::modified_gamma_um(f.a, f.alpha, f.b, f.gamma);
        else if constexpr (std::is_same_v<T, ExponentialDrops>)
          return SizeDistribution::exponential_diameter(f.n0_per_m3_per_mm, f.lambda_per_mm);
        else {
          // n = c r^-nu with int n dr = 1 cm^-3 over [r_min, r_max].
          const double e = 1 - f.nu;
          const double integral = std::abs(e) < 1e-12 ? std::log(f.r_max_m / f.r_min_m)
                                                      : (std::pow(f.r_max_m, e) - std::pow(f.r_min_m, e)) / e;
          return SizeDistribution::power_law(kOnePerCm3 / integral, f.nu, f.r_min_m, f.r_max_m);
        }
      },
      p.family);
}

SizeDistribution condition_distribution(const MieCondition& c) {
  SizeDistribution d = std::visit(
      [](const auto& drops) -> SizeDistribution {
        using T = std::decay_t<decltype(drops)>;
        if constexpr (std::is_same_v<T, MarshallPalmerRain>) return SizeDistribution::marshall_palmer(drops.rate_mm_h);
        else if constexpr (std::is_same_v<T, FogPreset>) return preset_distribution(to_string(drops));
        else if constexpr (std::is_same_v<T, ParametricDrops>) return parametric_distribution(drops);
        else return read_distribution_csv(drops.path);
      },
      c.drops);
  if (const auto* n = std::get_if<NumberDensity>(&c.rescaling)) d = normalised_to_number(d, n->per_cm3 * 1e6);
  if (const auto* w = std::get_if<LiquidWaterContent>(&c.rescaling))
    d = normalised_to_water_content(d, w->g_per_m3 * 1e-3);
  return d;
}

std::complex<double> condition_refractive_index(const MieCondition& c, double wavelength_m, const Settings& s,
                                                std::string* source) {
  if (const auto* constant = std::get_if<ConstantIndex>(&c.index)) {
    if (source) *source = "constant m = " + g4(constant->m.real()) + "+" + g4(constant->m.imag()) + "i";
    return constant->m;
  }
  if (const auto* file = std::get_if<IndexFile>(&c.index)) {
    const MaterialIndex index = read_index_file(file->path);
    const auto m = index.at(wavelength_m);
    if (source)
      *source = "m = " + io::index_text(m) + " from '" + file->path + "' (" + index.description() +
                (index.citation().empty() ? "" : "; " + index.citation()) + ")";
    return m;
  }
  const auto* named = std::get_if<WaterTable>(&c.index);
  const auto& table = refractive_index_table(named ? to_string(*named) : s.water_table);
  const auto m = table.at(wavelength_m);
  if (source) {
    std::ostringstream o;
    o.precision(7);
    o << "m = " << m.real() << "+" << m.imag() << "i from " << table.name() << " (" << table.citation()
      << "), interpolated in ln(lambda)";
    *source = o.str();
  }
  return m;
}

BulkOptics condition_bulk_optics(const MieCondition& c, double wavelength_m, const Settings& s) {
  return bulk_optics_of(c, wavelength_m, s, condition_distribution(c),
                        condition_refractive_index(c, wavelength_m, s));
}

Sigma sigma(const Condition& condition, double wavelength_m, const Settings& s) {
  struct Visitor {
    double wavelength_m;
    const Settings& s;

    Sigma operator()(const ClearAir& c) const {
      Sigma out;
      out.convention = "n/a";
      if (c.visibility_m) {
        out.per_m = sigma_from_visibility_per_m(*c.visibility_m, s.contrast_threshold);
        out.model = "clear air from visibility " + koschmieder_words(*c.visibility_m, s);
      } else {
        out.per_m = kSeedClearSigmaPerM;
        out.model = "clear air, seed paper value 0.00015 1/m";
      }
      return out;
    }
    Sigma operator()(const Visibility& c) const {
      Sigma out;
      out.convention = "n/a";
      out.per_m = sigma_from_visibility_per_m(c.visibility_m, s.contrast_threshold);
      out.model = "visibility " + koschmieder_words(c.visibility_m, s);
      return out;
    }
    Sigma operator()(const GivenSigma& c) const {
      Sigma out;
      out.convention = "n/a";
      out.per_m = c.per_m;
      out.model = "given sigma";
      return out;
    }
    Sigma operator()(const RainPowerLaw& c) const {
      const auto& law = rain_power_law(c.law);
      const double published = law.k * std::pow(c.rate_mm_h, law.alpha);
      Sigma out;
      out.per_m = power_law_sigma_per_m(published, s.convention);
      out.convention = to_string(s.convention);
      out.model = "rain " + g4(c.rate_mm_h) + " mm/h, power law " + law.source + " = " + power_law_words(published, s);
      return out;
    }
    Sigma operator()(const Snow& c) const {
      const auto co = snow_coefficients(c.type, wavelength_m);
      const double published = co.a * std::pow(c.rate_mm_h, co.b);
      Sigma out;
      out.per_m = power_law_sigma_per_m(published, s.convention);
      out.convention = to_string(s.convention);
      out.model = to_string(c.type) + " snow " + g4(c.rate_mm_h) + " mm/h, P.1817-1 a S^b with a=" + g4(co.a) +
                  " b=" + g4(co.b) + " = " + power_law_words(published, s);
      return out;
    }
    Sigma operator()(const FogFromVisibility& c) const {
      const auto r = fog_from_visibility(c.model, c.visibility_m, wavelength_m);
      Sigma out;
      out.convention = "n/a";
      out.per_m = r.sigma_per_m;
      out.model = r.model + ", V=" + g4(c.visibility_m) + " m";
      out.note = r.warning;
      return out;
    }
    Sigma operator()(const MieCondition& c) const { return cached_mie_sigma(c, wavelength_m, s); }
    Sigma operator()(const AerosolCondition& c) const { return aerosol_sigma(c, wavelength_m, s); }
  };
  const Sigma out = std::visit(Visitor{wavelength_m, s}, condition);
  // The domains (domains.hpp) keep every model finite; this guards the promise
  // that no output carries inf or NaN.
  if (!std::isfinite(out.per_m) || !(out.per_m >= 0) || !std::isfinite(out.error_per_m))
    throw std::runtime_error("sigma of " + to_text(condition) + " at " + g4(wavelength_m * 1e9) + " nm is " +
                             g4(out.per_m) + " +- " + g4(out.error_per_m) + " 1/m, not a finite value (" + out.model +
                             ")");
  return out;
}

}  // namespace attenuvis::weather
