// The bulk optics and sigma of aerosol conditions (aerosol_optics.hpp).
#include "attenuvis/weather/aerosol_optics.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/segmented_contour.hpp"

namespace attenuvis::weather {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kPerCm3 = 1e6;           // m^-3
constexpr double kScalingWavelength = 550e-9;  // the visibility of a scaling is Koschmieder's at 550 nm

std::string g4(double v) { return io::significant(v, 4); }

// Per-particle optics (one particle per cm^3) of a population state, per
// process.  Bounded: a long sweep with angular quantities must not hold
// every state it ever saw (a few kB each).
class PerParticleMemo {
 public:
  template <class Compute>
  BulkOptics get(const std::string& key, Compute compute) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = values_.find(key); it != values_.end()) return it->second;
    }
    BulkOptics v = compute();
    std::lock_guard<std::mutex> lock(mutex_);
    if (values_.size() >= kMaxEntries) values_.clear();
    values_.emplace(key, v);
    return v;
  }

 private:
  static constexpr std::size_t kMaxEntries = 20000;
  std::mutex mutex_;
  std::map<std::string, BulkOptics> values_;
};

QuadratureSettings population_settings(const Settings& s, const OpticsRequest& r) {
  QuadratureSettings q;
  q.rel_tolerance = s.rel_tolerance;
  q.max_evaluations = s.max_evaluations;
  q.cancel = s.cancel;
  q.backscatter = r.backscatter;
  q.legendre_moments = r.legendre_moments;
  q.angles_deg = r.angles_deg;
  q.polarised = r.polarised;
  return q;
}

std::string request_key(const OpticsRequest& r, double wavelength_m, const Settings& s) {
  std::string key = io::shortest(wavelength_m) + "|" + io::shortest(s.rel_tolerance) + "|" +
                    std::to_string(s.max_evaluations) + "|" +
                    (r.backscatter ? "b" : "") + "|" + std::to_string(r.legendre_moments) + (r.polarised ? "p" : "");
  for (double a : r.angles_deg) key += "," + io::shortest(a);
  return key;
}

// The efficiencies' own accuracy (mie.hpp, its referee tests: within 1e-10
// relative, floored at 1e-14 Q_ext), which the quadrature's |K - G| cannot
// see: for the smallest components at long wavelengths the quadrature
// converges to ~1e-15 of sigma, below what double-precision efficiencies
// promise.  Counted as each integral's rounding error, and in g's error.
void add_efficiency_accuracy(BulkOptics& b) {
  constexpr double kRelative = 1e-10, kFloor = 1e-14;
  const double ext = b.extinction.value;
  for (IntegralEstimate* e : {&b.extinction, &b.scattering, &b.absorption, &b.backscatter})
    e->rounding_error += kRelative * std::abs(e->value) + kFloor * ext;
  b.asymmetry_error += 2 * kRelative * std::abs(b.asymmetry) + kFloor;
  if (b.extinction.value > 0) b.albedo_error += (b.scattering.rounding_error + b.albedo * b.extinction.rounding_error) / ext;
  if (b.backscatter_computed && b.backscatter.value > 0)
    b.lidar_ratio_error += b.lidar_ratio * (b.extinction.rounding_error / ext + b.backscatter.rounding_error /
                                                                                  b.backscatter.value);
}

BulkOptics per_particle_optics(const AerosolPopulation& p, double wavelength_m, const Settings& s,
                               const OpticsRequest& r) {
  static PerParticleMemo memo;
  return memo.get(p.key() + "|" + request_key(r, wavelength_m, s), [&] {
    BulkOptics b = mie_bulk_optics(population_distribution(p, 1.0), wavelength_m, p.index_at(wavelength_m),
                                   population_settings(s, r));
    add_efficiency_accuracy(b);
    return b;
  });
}

// sigma_ext alone of one particle per cm^3 of a population.  A truncated
// log-normal is analytic between its cuts, so the segmented contour applies
// (one piece, a vertical leg at each cut; segmented_contour.hpp): its path
// stays H = 4 above the resonances, which the real axis must resolve one by
// one for nearly lossless particles (coarse sea salt at 550 nm: ~1e4 poles
// and 1-2 s at 1e-4 on the real axis, ~600 evaluations and 3 ms by the
// contour).  Where the contour does not apply (x beyond its range) or its
// estimate exceeds the evaluation budget, the real axis computes it.
BulkOptics per_particle_extinction(const AerosolPopulation& p, double wavelength_m, const Settings& s) {
  static PerParticleMemo memo;
  return memo.get(p.key() + "|ext|" + io::shortest(wavelength_m) + "|" + io::shortest(s.rel_tolerance) + "|" +
                      std::to_string(s.max_evaluations),
                  [&] {
                    const SizeDistribution d = population_distribution(p, 1.0);
                    SegmentedContourSettings cs;
                    cs.rel_tolerance = s.rel_tolerance;
                    cs.max_evaluations = s.max_evaluations;
                    cs.cancel = s.cancel;
                    cs.truncated_log_normal = true;
                    const double estimate = segmented_contour_cost(d, wavelength_m, cs).evaluations;
                    if (estimate > 0 && estimate <= static_cast<double>(s.max_evaluations))
                      if (const auto c = segmented_contour_extinction(d, wavelength_m, p.index_at(wavelength_m), cs)) {
                        BulkOptics b;
                        b.extinction = c->extinction;
                        b.evaluations = c->evaluations;
                        b.max_size_parameter = c->max_size_parameter;
                        b.method = c->method;
                        return b;
                      }
                    return per_particle_optics(p, wavelength_m, s, OpticsRequest{false, -1, {}, false});
                  });
}

// The mixture of c's parts as given (unscaled), from per-particle optics, or
// sigma_ext alone when `extinction_only`.
BulkOptics unscaled_optics(const std::vector<AerosolPart>& parts, double wavelength_m, const Settings& s,
                           const OpticsRequest& r, bool extinction_only = false) {
  std::vector<BulkOptics> each;
  each.reserve(parts.size());
  std::vector<const BulkOptics*> optics;
  std::vector<double> numbers;
  for (const AerosolPart& part : parts)
    each.push_back(extinction_only ? per_particle_extinction(part.population, wavelength_m, s)
                                   : per_particle_optics(part.population, wavelength_m, s, r));
  for (std::size_t j = 0; j < parts.size(); ++j) {
    optics.push_back(&each[j]);
    numbers.push_back(parts[j].per_cm3);
  }
  return external_mixture(optics, numbers);
}

struct Scale {
  double factor = 1, relative_error = 0;
  std::string words;
};

Scale number_scale(const AerosolCondition& c, const std::vector<AerosolPart>& parts, const Settings& s) {
  if (const auto* v = std::get_if<ScaledToVisibility>(&c.scaling)) {
    const BulkOptics at550 = unscaled_optics(parts, kScalingWavelength, s, {}, true);
    const double wanted = -std::log(s.contrast_threshold) / v->visibility_m;
    const double sigma = at550.extinction.value;
    if (!(sigma > 0)) throw std::invalid_argument(aerosol_words(c) + " has no extinction at 550 nm to scale");
    return {wanted / sigma, at550.extinction.error() / sigma,
            "number densities x " + g4(wanted / sigma) + " for a visibility of " + g4(v->visibility_m) +
                " m at 550 nm (Koschmieder, threshold " + g4(s.contrast_threshold) + ")"};
  }
  if (const auto* m = std::get_if<ScaledToDryMass>(&c.scaling)) {
    const double f = m->ug_per_m3 / aerosol_dry_mass_ug_m3(c);
    return {f, 0, "number densities x " + g4(f) + " for a dry mass of " + g4(m->ug_per_m3) + " ug/m^3"};
  }
  return {};
}

// Scales the extensive quantities of b by f, known to `relative_error` (the
// 550 nm quadrature of a visibility scaling, which adds to each one's
// quadrature error); the normalised ones do not change.
void scale_optics(BulkOptics& b, double f, double relative_error) {
  for (IntegralEstimate* e : {&b.extinction, &b.scattering, &b.absorption, &b.backscatter}) {
    auto& [value, quadrature, tail, asymptotic, resonance, rounding] = *e;
    for (double* x : {&value, &quadrature, &tail, &asymptotic, &resonance, &rounding}) *x *= f;
    quadrature += std::abs(value) * relative_error;
  }
}

std::string amounts_words(const AerosolCondition& c) {
  std::string out;
  for (const AerosolAmount& a : c.amounts) out += (out.empty() ? "" : ", ") + to_string(a.component) + " " + g4(a.per_cm3);
  return out + " cm^-3";
}

std::string index_words(const std::vector<AerosolPart>& parts, double wavelength_m) {
  std::string out = "OPAC refractive indices (data/opac) at " + g4(wavelength_m * 1e9) + " nm:";
  for (const AerosolPart& p : parts) out += " " + p.population.describe() + " m = " + io::index_text(p.population.index_at(wavelength_m)) + ";";
  return out;
}

}  // namespace

std::vector<AerosolPart> aerosol_parts(const AerosolCondition& c) {
  std::vector<AerosolPart> out;
  for (const AerosolAmount& a : c.amounts)
    for (const AerosolPopulation& p : component_populations(a.component, c.relative_humidity_percent, c.humidity_rule))
      out.push_back({p, a.per_cm3 * p.weight});
  return out;
}

SizeDistribution population_distribution(const AerosolPopulation& p, double per_cm3) {
  return SizeDistribution::truncated_log_normal(per_cm3 * kPerCm3, p.r_mod_m, p.sigma_g, p.r_min_m, p.r_max_m);
}

double aerosol_dry_mass_ug_m3(const AerosolCondition& c) {
  double kg_per_m3 = 0;
  for (const AerosolAmount& a : c.amounts) {
    const std::vector<AerosolPopulation> dry = component_populations(a.component, 0, HumidityRule::nearest);
    ATTENUVIS_CHECK_EQ(dry.size(), 1u);
    kg_per_m3 += dry.front().density_kg_m3 * 4.0 / 3.0 * kPi * population_distribution(dry.front(), a.per_cm3).moment(3);
  }
  return kg_per_m3 * 1e9;
}

std::string aerosol_words(const AerosolCondition& c) {
  const std::string what = c.mixture ? "OPAC " + info(*c.mixture).help + " aerosol" : "aerosol";
  return what + " at " + g4(c.relative_humidity_percent) + " % RH (" + to_string(c.humidity_rule) + " growth)";
}

namespace {

AerosolOptics mixture_optics(const AerosolCondition& c, double wavelength_m, const Settings& s,
                             const OpticsRequest& request, bool extinction_only) {
  const std::vector<AerosolPart> parts = aerosol_parts(c);
  const Scale scale = number_scale(c, parts, s);
  AerosolOptics out;
  out.bulk = unscaled_optics(parts, wavelength_m, s, request, extinction_only);
  scale_optics(out.bulk, scale.factor, scale.relative_error);
  out.number_scale = scale.factor;
  out.scale_error = scale.relative_error;
  out.model = aerosol_words(c) + ": " + amounts_words(c) + (scale.words.empty() ? "" : "; " + scale.words) +
              " (" + opac_citation() + ")";
  out.index_source = index_words(parts, wavelength_m);
  return out;
}

}  // namespace

AerosolOptics aerosol_optics(const AerosolCondition& c, double wavelength_m, const Settings& s,
                             const OpticsRequest& request) {
  check_scattering_angles(request.angles_deg);
  if (request.legendre_moments < -1) throw std::invalid_argument("Legendre moments: L must be >= 0");
  return mixture_optics(c, wavelength_m, s, request, false);
}

Sigma aerosol_sigma(const AerosolOptics& o) {
  const IntegralEstimate& e = o.bulk.extinction;
  Sigma out;
  out.convention = "n/a";
  out.per_m = e.value;
  out.error_per_m = e.error();
  out.error_terms = {{o.scale_error > 0 ? "quadrature (with the 550 nm scaling integral)" : "quadrature",
                      e.quadrature_error},
                     {"tails", e.tail_error},
                     {"unresolved resonances, or the contour's near-axis bound", e.resonance_error},
                     {"rounding of the Mie efficiencies or of S(0) on the contour", e.rounding_error}};
  out.model = "Mie over " + o.model;
  out.note = o.index_source + " " + o.bulk.method;
  if (!std::isfinite(out.per_m) || !(out.per_m >= 0) || !std::isfinite(out.error_per_m))
    throw std::runtime_error("sigma of " + o.model + " is " + g4(out.per_m) + " +- " + g4(out.error_per_m) +
                             " 1/m, not a finite value");
  return out;
}

Sigma aerosol_sigma(const AerosolCondition& c, double wavelength_m, const Settings& s) {
  return aerosol_sigma(mixture_optics(c, wavelength_m, s, {}, true));
}

}  // namespace attenuvis::weather
