// sigma for every kind of condition.
#include "attenuvis/weather/sigma.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/distribution_file.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/visibility.hpp"
#include "significant.hpp"

namespace attenuvis::weather {
namespace {
std::string g4(double v) { return detail::significant(v, 4); }
}  // namespace

SizeDistribution condition_distribution(const Condition& c) {
  if (!c.needs_mie()) throw std::invalid_argument("condition '" + c.text + "' has no size distribution");
  SizeDistribution d = c.kind == ConditionKind::rain_mie ? SizeDistribution::marshall_palmer(c.value)
                       : c.model.rfind("file=", 0) == 0  ? read_distribution_csv(c.model.substr(5))
                                                         : preset_distribution(c.model);
  if (c.number_per_cm3 > 0) d = normalised_to_number(d, c.number_per_cm3 * 1e6);
  if (c.lwc_g_m3 > 0) d = normalised_to_water_content(d, c.lwc_g_m3 * 1e-3);
  return d;
}

std::complex<double> condition_refractive_index(const Condition& c, const Settings& s, std::string* source) {
  if (c.refractive_index) {
    if (source) *source = "constant m = " + g4(c.refractive_index->real()) + "+" + g4(c.refractive_index->imag()) + "i";
    return *c.refractive_index;
  }
  const auto& table = refractive_index_table(c.water_table.empty() ? s.water_table : c.water_table);
  auto m = table.at(s.wavelength_m);
  if (source) {
    std::ostringstream o;
    o.precision(7);
    o << "m = " << m.real() << "+" << m.imag() << "i from " << table.name() << " (" << table.citation()
      << "), interpolated in ln(lambda)";
    *source = o.str();
  }
  return m;
}

namespace {
// The real-axis quadrature of a Mie condition, over a distribution and index
// the caller already has (sigma() needs them for the contour first).
BulkOptics bulk_optics_of(const Condition& c, const Settings& s, const SizeDistribution& d,
                          std::complex<double> m) {
  QuadratureSettings q;
  q.rel_tolerance = s.rel_tolerance;
  if (c.kind == ConditionKind::rain_mie) {
    // Rain's error is dominated by the large-x bound (~5e-3 relative), so the
    // resonances need not be refined below 1e-3 of sigma.
    q.asymptotic_x = s.rain_asymptotic_x;
    q.resonance_tolerance = 1e-3;
    q.max_evaluations = 1000000;
  }
  return integrate_bulk_optics(d, s.wavelength_m, mie_efficiencies(m), q, m);
}
}  // namespace

BulkOptics condition_bulk_optics(const Condition& c, const Settings& s) {
  return bulk_optics_of(c, s, condition_distribution(c), condition_refractive_index(c, s));
}

Sigma sigma(const Condition& c, const Settings& s) {
  Sigma out;
  out.convention = "n/a";
  switch (c.kind) {
    case ConditionKind::clear:
      if (c.value > 0) {
        out.per_m = sigma_from_visibility_per_m(c.value, s.contrast_threshold);
        out.model = "clear air from visibility " + g4(c.value) + " m (Koschmieder, threshold " +
                    g4(s.contrast_threshold) + ")";
      } else {
        out.per_m = kSeedClearSigmaPerM;
        out.model = "clear air, seed paper value 0.00015 1/m";
      }
      break;
    case ConditionKind::visibility:
      out.per_m = sigma_from_visibility_per_m(c.value, s.contrast_threshold);
      out.model = "visibility " + g4(c.value) + " m (Koschmieder, threshold " + g4(s.contrast_threshold) + ")";
      break;
    case ConditionKind::sigma:
      out.per_m = c.value;
      out.model = "given sigma";
      break;
    case ConditionKind::rain_power_law: {
      const auto& law = rain_power_law(c.model);
      double published = law.k * std::pow(c.value, law.alpha);
      out.per_m = power_law_sigma_per_m(published, s.convention);
      out.convention = to_string(s.convention);
      out.model = "rain " + g4(c.value) + " mm/h, power law " + law.source + " = " + g4(published) +
                  (s.convention == Convention::itu ? " dB/km" : " 1/km (seed reading)");
      break;
    }
    case ConditionKind::snow: {
      auto co = snow_coefficients(c.snow, s.wavelength_m);
      double published = co.a * std::pow(c.value, co.b);
      out.per_m = power_law_sigma_per_m(published, s.convention);
      out.convention = to_string(s.convention);
      out.model = std::string(c.snow == SnowType::wet ? "wet" : "dry") + " snow " + g4(c.value) +
                  " mm/h, P.1817-1 a S^b with a=" + g4(co.a) + " b=" + g4(co.b) + " = " + g4(published) +
                  (s.convention == Convention::itu ? " dB/km" : " 1/km (seed reading)");
      break;
    }
    case ConditionKind::fog_visibility: {
      auto r = fog_from_visibility(c.fog_model, c.value, s.wavelength_m);
      out.per_m = r.sigma_per_m;
      out.model = r.model + ", V=" + g4(c.value) + " m";
      out.note = r.warning;
      break;
    }
    case ConditionKind::rain_mie:
    case ConditionKind::fog_mie: {
      // Mie integrals of near-lossless drops take seconds; a process asking for
      // the same condition twice (an app, a table with repeated rows) reuses it.
      // The key holds everything the result depends on (file contents aside).
      static std::mutex cache_mutex;
      static std::map<std::string, Sigma> cache;
      std::ostringstream key;
      key.precision(17);
      key << c.text << "|" << s.wavelength_m << "|" << s.rel_tolerance << "|" << s.water_table << "|"
          << s.rain_asymptotic_x;
      if (c.model.rfind("file=", 0) != 0) {
        std::lock_guard<std::mutex> lock(cache_mutex);
        if (auto it = cache.find(key.str()); it != cache.end()) return it->second;
      }
      std::string index_source;
      const std::complex<double> m = condition_refractive_index(c, s, &index_source);
      const SizeDistribution d = condition_distribution(c);
      out.model = "Mie over " + d.describe();
      std::ostringstream note;
      note.precision(3);
      // Analytic distributions within reach: integrate above the real axis,
      // where Q_ext's resonances are smooth (contour_extinction.hpp); else on
      // the real axis with the resonances as an error term (bulk_optics.hpp).
      ContourSettings cs;
      cs.rel_tolerance = s.rel_tolerance;
      if (const auto ce = contour_extinction(d, s.wavelength_m, m, cs)) {
        out.per_m = ce->extinction.value;
        out.error_per_m = ce->extinction.error();
        note << index_source << "; " << ce->method << "; error = quadrature " << ce->extinction.quadrature_error
             << " + tails " << ce->extinction.tail_error << " + rounding " << ce->extinction.rounding_error;
      } else {
        const BulkOptics b = bulk_optics_of(c, s, d, m);
        out.per_m = b.extinction.value;
        out.error_per_m = b.extinction.error();
        note << index_source << "; " << b.method << "; error = quadrature " << b.extinction.quadrature_error
             << " + tails " << b.extinction.tail_error << " + unresolved resonances " << b.extinction.resonance_error;
        if (b.extinction.asymptotic_error > 0) note << " + large-x expansion " << b.extinction.asymptotic_error;
      }
      note << " 1/m";
      out.note = note.str();
      if (c.model.rfind("file=", 0) != 0) {
        std::lock_guard<std::mutex> lock(cache_mutex);
        cache[key.str()] = out;
      }
      break;
    }
  }
  return out;
}

}  // namespace attenuvis::weather
