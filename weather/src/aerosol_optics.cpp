// The bulk optics and sigma of aerosol conditions (aerosol_optics.hpp).
#include "attenuvis/weather/aerosol_optics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/segmented_contour.hpp"
#include "bulk_components.hpp"

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

// `looser` >= 1 multiplies both tolerances (tolerance_factors).
QuadratureSettings population_settings(const Settings& s, const OpticsRequest& r, double looser) {
  QuadratureSettings q;
  q.rel_tolerance = s.rel_tolerance * looser;
  if (looser > 1) q.angular_tolerance = std::max(s.rel_tolerance, 1e-6) * looser;
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
constexpr double kEfficiencyRelative = 1e-10;
void add_efficiency_accuracy(BulkOptics& b) {
  constexpr double kRelative = kEfficiencyRelative, kFloor = 1e-14;
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
                               const OpticsRequest& r, double looser = 1) {
  static PerParticleMemo memo;
  return memo.get(p.key() + "|" + request_key(r, wavelength_m, s) + "|x" + io::shortest(looser), [&] {
    BulkOptics b = mie_bulk_optics(population_distribution(p, 1.0), wavelength_m, p.index_at(wavelength_m),
                                   population_settings(s, r, looser));
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

// The loosest tolerance a population of a mixture is given.
constexpr double kLoosestTolerance = 0.5;

// How much looser than the mixture's own tolerance each population's may
// be.  A population adds to every quantity of the mixture about its share
// of the mixture's sigma_ext (sigma_sca, beta_pi and the moments of these
// scattering-dominated particles follow it), so with P populations one
// holding a share e may carry 1/(P e) times the relative error: each then
// spends at most about 1/P of the mixture's budget, and a minor mode of
// nearly lossless particles (coarse sea salt in maritime air, <1 % of
// sigma_ext) no longer resolves its own resonances to the mixture's
// tolerance.  At least 1 (the dominant populations keep the tolerance), at
// most what keeps the tolerances <= kLoosestTolerance.  The shares come from
// sigma_ext by the contour (milliseconds); whether the mixture meets its
// tolerance is checked on its reported errors (mixture_missed).
std::vector<double> tolerance_factors(const std::vector<AerosolPart>& parts, double wavelength_m, const Settings& s) {
  std::vector<double> factors(parts.size(), 1.0);
  const double most = kLoosestTolerance / std::max(s.rel_tolerance, 1e-6);
  if (parts.size() < 2 || !(most > 1)) return factors;
  std::vector<double> ext(parts.size());
  double total = 0;
  for (std::size_t j = 0; j < parts.size(); ++j) {
    ext[j] = parts[j].per_cm3 * per_particle_extinction(parts[j].population, wavelength_m, s).extinction.value;
    total += ext[j];
  }
  if (!(total > 0) || !std::isfinite(total)) return factors;
  const double P = static_cast<double>(parts.size());
  for (std::size_t j = 0; j < parts.size(); ++j)
    factors[j] = ext[j] > 0 ? std::clamp(total / (P * ext[j]), 1.0, most) : most;
  return factors;
}

// Which quantity of a mixture misses its tolerance by its reported error, the
// worst, in words; empty when none does.  The tolerances of bulk_optics.hpp:
// sigma_ext, sigma_sca, sigma_abs relative to sigma_ext; g and the matrix
// expansion's coefficients absolute, beta_pi and p(theta) relative, chi_l
// relative down to |chi_l| = 1e-3 (Layout::moment_scale), to
// max(tolerance, 1e-6).
std::string mixture_missed(const BulkOptics& b, const Settings& s) {
  const double tol = s.rel_tolerance, angular = std::max(tol, 1e-6), ext = b.extinction.value;
  std::string worst;
  double worst_ratio = 1, worst_tol = tol;
  const auto check = [&](const std::string& name, double error, double allowed, double t) {
    const double ratio = allowed > 0 ? error / allowed : 0;
    if (ratio > worst_ratio) worst = name, worst_ratio = ratio, worst_tol = t;
  };
  check("sigma_ext", b.extinction.error(), tol * ext, tol);
  if (b.scattering_computed) {
    check("sigma_sca", b.scattering.error(), tol * ext, tol);
    check("sigma_abs", b.absorption.error(), tol * ext, tol);
    check("asymmetry g", b.asymmetry_error, angular, angular);
  }
  if (b.backscatter_computed)
    check("backscatter beta_pi", b.backscatter.error(), angular * b.backscatter.value, angular);
  for (std::size_t l = 1; l < b.moments_error.size(); ++l)
    check("Legendre moment chi_" + std::to_string(l), b.moments_error[l],
          angular * detail::Layout::moment_scale(b.moments[l]), angular);
  for (std::size_t i = 0; i < b.phase_error.size() && i < b.angles_deg.size(); ++i)
    check("phase function at " + g4(b.angles_deg[i]) + " deg", b.phase_error[i], angular * b.phase[i], angular);
  const auto& [a1, a2, a3, a4, b1, b2] = b.expansion_error;
  for (const std::vector<double>* part : {&a1, &a2, &a3, &a4, &b1, &b2})
    for (std::size_t l = 0; l < part->size(); ++l)
      check("scattering-matrix expansion coefficient of order " + std::to_string(l), (*part)[l], angular, angular);
  if (worst.empty()) return {};
  return worst + " of the aerosol: relative tolerance " + io::significant(worst_tol, 3) +
         " not met (error reached " + io::significant(worst_ratio, 3) + " times that, as reported)";
}

// The external mixture of `each`, population j's optics per particle, in
// parts[j]'s numbers.
BulkOptics mixture_of(const std::vector<AerosolPart>& parts, const std::vector<BulkOptics>& each) {
  std::vector<const BulkOptics*> optics;
  std::vector<double> numbers;
  for (std::size_t j = 0; j < parts.size(); ++j) {
    optics.push_back(&each[j]);
    numbers.push_back(parts[j].per_cm3);
  }
  return external_mixture(optics, numbers);
}

// The mixture of the per-particle optics of `parts`, population j's to its
// tolerance times factors[j] (`each`: the populations' own results).
BulkOptics mixed(const std::vector<AerosolPart>& parts, double wavelength_m, const Settings& s, const OpticsRequest& r,
                 const std::vector<double>& factors, std::vector<BulkOptics>& each) {
  each.clear();
  for (std::size_t j = 0; j < parts.size(); ++j)
    each.push_back(per_particle_optics(parts[j].population, wavelength_m, s, r, factors[j]));
  return mixture_of(parts, each);
}

// The mixture of c's parts as given (unscaled), from per-particle optics, or
// sigma_ext alone when `extinction_only`.  With several populations, each
// takes a tolerance by its share (tolerance_factors); if the mixture then
// misses its tolerance by its reported errors, the loosened populations that
// met theirs are computed again to the mixture's own tolerance, and the
// mixture's verdict comes first in the result's shortfall.
BulkOptics unscaled_optics(const std::vector<AerosolPart>& parts, double wavelength_m, const Settings& s,
                           const OpticsRequest& r, bool extinction_only = false) {
  std::vector<BulkOptics> each;
  if (extinction_only) {
    for (const AerosolPart& part : parts) each.push_back(per_particle_extinction(part.population, wavelength_m, s));
    return mixture_of(parts, each);
  }
  std::vector<double> factors = tolerance_factors(parts, wavelength_m, s);
  BulkOptics out = mixed(parts, wavelength_m, s, r, factors, each);
  std::string missed = mixture_missed(out, s);
  // Tighter tolerances help only the loosened populations that met theirs
  // (one that fell short, its resonances beyond the budget, would again),
  // and only above the efficiencies' own accuracy, which is in every error.
  const bool tighten = s.rel_tolerance > 2 * kEfficiencyRelative;
  bool loosened = false;
  for (std::size_t j = 0; j < parts.size(); ++j)
    if (factors[j] > 1 && each[j].shortfall.empty()) loosened = true;
  if (!missed.empty() && tighten && loosened) {
    for (std::size_t j = 0; j < parts.size(); ++j)
      if (each[j].shortfall.empty()) factors[j] = 1;
    out = mixed(parts, wavelength_m, s, r, factors, each);
    missed = mixture_missed(out, s);
  }
  // What the populations missed: all of it after the mixture's verdict when
  // the mixture misses; otherwise only what those asked for the mixture's own
  // tolerance missed (a loosened population's miss is within the mixture's).
  for (std::size_t j = 0; j < parts.size(); ++j)
    if (!each[j].shortfall.empty() && (!missed.empty() || factors[j] == 1))
      missed += (missed.empty() ? "" : "; ") + parts[j].population.describe() + ": " + each[j].shortfall;
  out.shortfall = missed;
  if (std::any_of(factors.begin(), factors.end(), [](double f) { return f > 1; })) {
    std::string words;
    for (std::size_t j = 0; j < parts.size(); ++j)
      words += (j ? ", " : "") + parts[j].population.describe() + " x" + g4(factors[j]);
    out.method += "; population tolerances loosened by their share of sigma_ext (" + words + ")";
  }
  if (!missed.empty()) out.method += "; tolerance not met: " + missed;
  return out;
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
  out.shortfall = o.bulk.shortfall;
  if (!std::isfinite(out.per_m) || !(out.per_m >= 0) || !std::isfinite(out.error_per_m))
    throw std::runtime_error("sigma of " + o.model + " is " + g4(out.per_m) + " +- " + g4(out.error_per_m) +
                             " 1/m, not a finite value");
  return out;
}

Sigma aerosol_sigma(const AerosolCondition& c, double wavelength_m, const Settings& s) {
  return aerosol_sigma(mixture_optics(c, wavelength_m, s, {}, true));
}

}  // namespace attenuvis::weather
