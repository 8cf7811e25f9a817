// Particle size distributions n(r) = dN/dr.
//
// Internally everything is SI: radius r in metres and n(r) in m^-4 (particles
// per m^3 of air per metre of radius).  Constructors take the units the
// literature uses and say so in their names.
//
// Families (each has exact moments and exact tail moments, which is what lets
// the extinction integral bound its truncated tails):
//   modified gamma   n = a r^alpha exp(-b r^gamma)    (Deirmendjian 1969; P.1817-1 uses gamma = 1)
//   log-normal       n = N / (sqrt(2 pi) ln(sg) r) exp(-(ln r - ln rg)^2 / (2 ln^2 sg)), optionally
//                    cut to [r_min, r_max] (OPAC's components, Hess et al. 1998, Sec. 3c: N stays the
//                    number of the whole log-normal, the integrals run between the cut-offs)
//   exponential      N(D) = N0 exp(-Lambda D) in diameter: Marshall & Palmer (1948) rain,
//                    Gunn & Marshall (1958) snow; a modified gamma with alpha = 0, gamma = 1
//   power law        n = C r^-nu on [r_min, r_max]  (Junge)
//   tabulated        piecewise linear n(r) from a CSV file (points or bins), zero outside
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace attenuvis::weather {

// n = a t^alpha exp(-b t^gamma) m^-4 with t = r / r0 (r0 keeps b finite for large gamma).
struct ModifiedGamma { double a, alpha, b, gamma, r0 = 1.0; };
// r_min_m = 0 and r_max_m = inf: no cut-off.  With cut-offs the density is
// zero outside [r_min_m, r_max_m] and number_per_m3 is still the number of
// the uncut log-normal.
struct LogNormal {
  double number_per_m3, median_radius_m, sigma_g;
  double r_min_m = 0, r_max_m = std::numeric_limits<double>::infinity();
  bool truncated() const { return r_min_m > 0 || r_max_m < std::numeric_limits<double>::infinity(); }
};
struct PowerLaw { double c, nu, r_min_m, r_max_m; };      // SI: n = c r^-nu
// One straight piece of a tabulated n(r): n goes linearly from n0 at r0 to n1 at r1.
struct TabulatedSegment { double r0, r1, n0, n1; };
struct Tabulated { std::vector<TabulatedSegment> segments; std::string source; };

// Where a distribution lives for an integral weighted by r^p: radii
// r_0 < ... < r_n between which the density is smooth, and the exact moment
// of order p that lies outside [r_0, r_n] (the truncated tails).
struct Support {
  std::vector<double> breakpoints_m;
  double omitted_moment = 0;  // integral of r^p n(r) outside [r_0, r_n], SI
  double total_moment = 0;    // integral of r^p n(r) over all r, SI
};

// A size distribution n(r) (m^-4) in one of the forms above, with its support.
class SizeDistribution {
 public:
  using Form = std::variant<ModifiedGamma, LogNormal, PowerLaw, Tabulated>;

  // P.1817-1 / seed-paper units: r in micrometres, n in cm^-3 um^-1.
  static SizeDistribution modified_gamma_um(double a, double alpha, double b, double gamma = 1.0);
  // A gamma distribution with `number_per_m3` particles, shape alpha and mode radius.
  static SizeDistribution gamma(double number_per_m3, double alpha, double mode_radius_m);
  static SizeDistribution log_normal(double number_per_m3, double median_radius_m, double sigma_g);
  // The same cut to [r_min_m, r_max_m]; number_per_m3 is that of the uncut log-normal.
  static SizeDistribution truncated_log_normal(double number_per_m3, double median_radius_m, double sigma_g,
                                               double r_min_m, double r_max_m);
  // N(D) = N0 exp(-Lambda D), N0 in m^-3 mm^-1, Lambda in mm^-1, D the diameter.
  static SizeDistribution exponential_diameter(double n0_per_m3_per_mm, double lambda_per_mm);
  // Marshall & Palmer (1948), J. Meteor. 5, 165: N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1.
  static SizeDistribution marshall_palmer(double rain_rate_mm_h);
  // Gunn & Marshall (1958), J. Meteor. 15, 452: N0 = 3800 R^-0.87 m^-3 mm^-1, Lambda = 2.55 R^-0.48 mm^-1,
  // R the melted-water precipitation rate (mm/h), D the melted diameter.
  static SizeDistribution gunn_marshall(double rate_mm_h);
  static SizeDistribution power_law(double c_si, double nu, double r_min_m, double r_max_m);
  static SizeDistribution tabulated(std::vector<TabulatedSegment> segments, std::string source);

  explicit SizeDistribution(Form form, std::string name = "") : form_(std::move(form)), name_(std::move(name)) {}

  double density(double r_m) const;             // n(r) in m^-4
  double moment(double p) const;                // integral r^p n(r) dr over all r, SI
  // Smallest interval holding all but a fraction `tail_fraction` of the p-th moment
  // (split evenly between the two tails); exact for every family.
  Support support(double p, double tail_fraction) const;

  SizeDistribution scaled(double factor) const;  // n -> factor n
  const Form& form() const { return form_; }
  const std::string& name() const { return name_; }
  std::string describe() const;                  // parameters in the units they were given

 private:
  Form form_;
  std::string name_;
};

// Named presets, listed once in distribution_presets() (the `distribution`
// command's help and Python's preset() read it):
//   advection, radiation   the fog presets below
//   marshall-palmer:R      rain at R mm/h;  gunn-marshall:R  snow at R mm/h (melted)
// Throws std::invalid_argument listing the presets.
SizeDistribution preset_distribution(const std::string& name);
bool is_preset_distribution(const std::string& name);

// The fog presets of ITU-R P.1817-1 (the seed paper's Table "Attenuation
// coefficient parameters for Fog"): modified gamma distributions
// n = a r^alpha exp(-b r), r in um, n in cm^-3 um^-1 (modified_gamma_um).
// The condition grammar's fog:advection and fog:radiation are these.
enum class FogPreset { advection, radiation };
struct FogPresetInfo {
  FogPreset id;
  std::string name;  // "advection": as the grammar, preset_distribution and Python spell it
  std::string help;  // "heavy advection fog"
  double a, alpha, b;
  std::string citation;
};
// Every fog preset, in the order of the enum.
const std::vector<FogPresetInfo>& fog_presets();
const FogPresetInfo& info(FogPreset p);
const FogPresetInfo* find_fog_preset(const std::string& name);  // nullptr for any other name
std::string to_string(FogPreset p);                              // its name: "advection" | "radiation"

// Every name preset_distribution takes, the fog presets first; a name ending
// in ":R" takes a rate there.
struct DistributionPresetInfo {
  std::string name;  // "advection", "marshall-palmer:R"
  std::string help;  // "heavy advection fog", "rain, R mm/h"
  std::string citation;
};
const std::vector<DistributionPresetInfo>& distribution_presets();

// Bulk properties.  Water content uses the bulk density given (liquid water
// 1000 kg/m^3; for ice pass 917).
struct Moments {
  double number_per_m3 = 0;
  double water_content_kg_m3 = 0;
  double effective_radius_m = 0;  // <r^3>/<r^2> (Hansen & Travis 1974)
  double mode_radius_m = 0;       // radius where n(r) peaks (0 if it peaks at r -> 0)
  double mean_radius_m = 0;
};
Moments moments(const SizeDistribution& d, double bulk_density_kg_m3 = 1000.0);

// The distribution scaled to a number density or to a water content.
SizeDistribution normalised_to_number(const SizeDistribution& d, double number_per_m3);
SizeDistribution normalised_to_water_content(const SizeDistribution& d, double kg_per_m3,
                                             double bulk_density_kg_m3 = 1000.0);

}  // namespace attenuvis::weather
