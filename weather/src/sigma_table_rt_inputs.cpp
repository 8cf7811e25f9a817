// A sigma table as the input of radiative-transfer codes.
//
// libRadtran (uvspec: wc_properties / ic_properties FILE, the netCDF table of
// its `mie` tool; read by read_mie_table in libsrc_c/miecalc.c, written by
// create_netcdf_file / write_output_netcdf in src/mie.c), classic netCDF:
//
//   global  file_info, version = 20110916 (its presence tells uvspec the file
//           holds several wavelengths), complete_moments (1 when every cell's
//           moments reach |(2l+1) chi_l| < 1e-5, the mie tool's test),
//           parameterization = "mie", size_distr, param_alpha = -999
//   dims    nlam, nreff, nmommax (L + 2: uvspec wants nmom < nmommax),
//           nphamat = 1, nthetamax, nrho = 1
//   wavelen(nlam)            um
//   reff(nreff)              um, the effective radius <r^3>/<r^2> of each
//                            condition's drops, increasing and equidistant
//                            (uvspec interpolates in it and checks the grid)
//   ext(nlam, nreff)         km^-1 / (g m^-3): sigma_ext per liquid (or ice)
//                            water content, sigma_ext[1/km] / LWC[g/m^3]
//   ssa(nlam, nreff)         sigma_sca / sigma_ext
//   nmom(nlam, nreff, nphamat)        int, moments that matter (see above)
//   pmom(nlam, nreff, nphamat, nmommax)  float, (2l + 1) chi_l: uvspec divides
//                            by 2l + 1 on reading ("including factor 2*l+1")
//   ntheta(nlam, nreff, nphamat)      int
//   theta(nlam, nreff, nphamat, nthetamax)  float, degrees, from 180 down to 0
//                            (uvspec refuses a grid that does not start at 180)
//   phase(nlam, nreff, nphamat, nthetamax)  float, p(theta), int p dOmega = 4 pi
//                            (the mie tool's mom2phase gives the same
//                            normalisation: p = sum (2l+1) chi_l P_l)
//   refre(nlam), refim(nlam) the index n + ik (uvspec does not read them)
//   rho(nlam, nreff)         g/cm^3, the bulk density behind ext
//   plus, ignored by uvspec: lwc(nreff) g/m^3, ext_error, ssa_error.
// nphamat = 1: the phase function alone.  A polarised table (nphamat 4: P11,
// P12, P33, P34 expanded in ordinary Legendre polynomials, Evans' signs; 6
// for non-spherical particles) is not written: attenuvis's polarised
// expansion is in generalised spherical functions (legendre_moments.hpp).
// The humidity axis of the aerosol tables (dimension nhum, variable hum in
// per cent, refre/refim over (nlam, nhum)) takes the place of nreff; a table
// of one aerosol over humidity would fill it from the same cells.
//
// DISORT (Stamnes et al. 1988; its inputs DTAUC, SSALB, PMOM of one layer):
// one line per cell, DTAUC = sigma_ext x the layer thickness, SSALB = omega_0,
// NMOM = L, PMOM(0..L) = chi_l (PMOM(0) = 1: DISORT's own normalisation, no
// 2l + 1).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/legendre.hpp>

#include "attenuvis/io/netcdf_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/detail/sigma_table_formats.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/sigma_table.hpp"

namespace attenuvis::weather {
namespace {

using io::significant;

// What a row of the libRadtran table stands for.
struct Row {
  std::size_t condition = 0;
  double reff_um = 0, lwc_g_m3 = 0, rho_g_cm3 = 1;
};

// Ice (Warren & Brandt) is 917 kg/m^3, everything else liquid water.
double bulk_density_kg_m3(const MieCondition& c, const Settings& s) {
  const WaterTableInfo* table = nullptr;
  if (const auto* named = std::get_if<WaterTable>(&c.index)) table = &info(*named);
  if (std::holds_alternative<SettingsWaterTable>(c.index)) table = find_water_table(s.water_table);
  return table && table->substance == "ice" ? 917.0 : 1000.0;
}

const MieCondition& mie_condition(const SigmaTable& t, std::size_t c, const char* format) {
  const auto* mie = std::get_if<MieCondition>(&t.conditions[c].condition);
  if (!mie)
    throw std::invalid_argument(std::string(format) + " tables describe drops: condition '" + t.conditions[c].label +
                                "' has no size distribution");
  return *mie;
}

void require_moments(const SigmaTable& t, const char* format) {
  if (t.max_moment < 0)
    throw std::invalid_argument(std::string(format) + " tables hold the Legendre moments of the phase function: add "
                                "moments:L to --quantities (e.g. moments:64)");
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c)
      if (std::isnan(table_moment(t.at(w, c), 0).value) || std::isnan(table_value(t.at(w, c), Quantity::ssa).value))
        throw std::invalid_argument(std::string(format) + " table: condition '" + t.conditions[c].label + "' at " +
                                    significant(wavelength_nm(t.wavelengths_m[w]), 6) +
                                    " nm has no moments or albedo (Q_ext's large-x expansion leaves no Q_sca)");
}

// The rows in increasing effective radius, on the equidistant grid uvspec
// demands (to 1e-6 of the step; then the grid's own values are written).
std::vector<Row> effective_radius_rows(const SigmaTable& t) {
  std::vector<Row> rows;
  for (std::size_t c = 0; c < t.conditions.size(); ++c) {
    const MieCondition& mie = mie_condition(t, c, "libradtran");
    const double density = bulk_density_kg_m3(mie, t.settings);
    const Moments m = moments(condition_distribution(mie), density);
    rows.push_back({c, m.effective_radius_m * 1e6, m.water_content_kg_m3 * 1e3, density * 1e-3});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.reff_um < b.reff_um; });
  if (rows.size() < 2) return rows;
  const double r0 = rows[0].reff_um, step = rows[1].reff_um - rows[0].reff_um;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double grid = r0 + static_cast<double>(i) * step;
    if (!(step > 0) || std::abs(rows[i].reff_um - grid) > 1e-6 * step)
      throw std::invalid_argument(
          "libradtran table: uvspec interpolates in the effective radius and needs it equidistant, but the "
          "conditions' r_eff start " + significant(r0, 8) + ", " + significant(rows[1].reff_um, 8) + " um and '" +
          t.conditions[rows[i].condition].label + "' has " + significant(rows[i].reff_um, 8) + " um where " +
          significant(grid, 8) + " um was due; choose drops whose effective radii are evenly spaced, or write "
          "one file per condition");
    rows[i].reff_um = grid;
  }
  return rows;
}

// The refractive index of every row at each wavelength: one per wavelength.
std::vector<std::complex<double>> shared_index(const SigmaTable& t, const std::vector<Row>& rows) {
  std::vector<std::complex<double>> out;
  for (double wavelength : t.wavelengths_m) {
    const auto first = condition_refractive_index(std::get<MieCondition>(t.conditions[rows[0].condition].condition),
                                                  wavelength, t.settings);
    for (const Row& r : rows) {
      const auto m = condition_refractive_index(std::get<MieCondition>(t.conditions[r.condition].condition),
                                                wavelength, t.settings);
      if (std::abs(m - first) > 1e-12 * std::abs(first))
        throw std::invalid_argument("libradtran table: its conditions must share one refractive index (a file is "
                                    "one substance), but '" + t.conditions[r.condition].label + "' differs from '" +
                                    t.conditions[rows[0].condition].label + "'");
    }
    out.push_back(first);
  }
  return out;
}

// How many of chi_0..chi_L matter: the first l with |(2l+1) chi_l| < 1e-5
// (libRadtran's mie tool's test), or L + 1 with `complete` false.
int significant_moments(const std::vector<double>& chi, bool& complete) {
  for (std::size_t l = 1; l < chi.size(); ++l)
    if (std::abs((2.0 * l + 1) * chi[l]) < 1e-5) return static_cast<int>(l);
  complete = false;
  return static_cast<int>(chi.size());
}

// chi_0..chi_L over chi_0, which is 1 but for rounding (the readers expect
// exactly 1: DISORT's PMOM(0), libRadtran's pmom(0), which its mie tool also
// divides out).
std::vector<double> cell_moments(const TableCell& cell, int L) {
  std::vector<double> chi;
  const double chi0 = table_moment(cell, 0).value;
  for (int l = 0; l <= L; ++l) chi.push_back(l == 0 ? 1.0 : table_moment(cell, l).value / chi0);
  return chi;
}

// theta from 180 down to 0 and p(theta): the table's phase function where it
// has one (its angles must reach 0 and 180), else the moments' sum on every
// degree, as libRadtran's mie tool writes it (mom2phase).
struct PhaseGrid {
  std::vector<double> theta;
  bool from_moments = false;
};
PhaseGrid phase_grid(const SigmaTable& t) {
  PhaseGrid g;
  if (t.angles_deg.empty()) {
    for (int a = 180; a >= 0; --a) g.theta.push_back(a);
    g.from_moments = true;
    return g;
  }
  if (t.angles_deg.front() != 0 || t.angles_deg.back() != 180)
    throw std::invalid_argument("libradtran table: uvspec reads the phase function from 180 degrees down to 0: "
                                "--angles must start at 0 and end at 180");
  g.theta.assign(t.angles_deg.rbegin(), t.angles_deg.rend());
  return g;
}
std::vector<double> cell_phase(const SigmaTable& t, const TableCell& cell, const PhaseGrid& g) {
  std::vector<double> p;
  if (!g.from_moments) {
    for (std::size_t i = t.angles_deg.size(); i-- > 0;) p.push_back(table_phase(cell, i).value);
    return p;
  }
  const std::vector<double> chi = cell_moments(cell, t.max_moment);
  const double pi = boost::math::constants::pi<double>();
  for (double theta : g.theta) {
    const double mu = std::cos(theta * pi / 180);
    // P_0..P_L by one upward recurrence (Bonnet), not each from P_0 again.
    double sum = 0, p_before = 0, p_l = 1;
    for (std::size_t l = 0; l < chi.size(); ++l) {
      sum += (2.0 * l + 1) * chi[l] * p_l;
      const double p_next = boost::math::legendre_next(static_cast<unsigned>(l), mu, p_l, p_before);
      p_before = p_l;
      p_l = p_next;
    }
    p.push_back(sum);
  }
  return p;
}

// The variables of libRadtran's table, in uvspec's units: per wavelength
// (wavelen, refre, refim), per effective radius (reff, lwc) and per cell,
// wavelength-major (ext per water mass, ssa, rho, nmom, pmom with 2l+1,
// theta and phase), and whether every cell's moments are complete.
struct LibradtranColumns {
  std::vector<double> wavelen, reff, lwc, ext, ext_error, ssa, ssa_error, refre, refim, rho;
  std::vector<int> nmom, nth;
  std::vector<float> pmom, theta, phase;
  bool complete = true;
};
LibradtranColumns libradtran_columns(const SigmaTable& t, const std::vector<Row>& rows,
                                     const std::vector<std::complex<double>>& index, const PhaseGrid& grid,
                                     std::size_t nmommax) {
  LibradtranColumns c;
  for (const Row& r : rows) c.reff.push_back(r.reff_um), c.lwc.push_back(r.lwc_g_m3);
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w) {
    c.wavelen.push_back(wavelength_nm(t.wavelengths_m[w]) * 1e-3);
    c.refre.push_back(index[w].real());
    c.refim.push_back(index[w].imag());
    for (const Row& r : rows) {
      const TableCell& cell = t.at(w, r.condition);
      // sigma_ext in 1/km per g/m^3 of condensed water.
      const QuantityValue sigma = table_value(cell, Quantity::sigma_ext), albedo = table_value(cell, Quantity::ssa);
      c.ext.push_back(sigma.value * 1e3 / r.lwc_g_m3);
      c.ext_error.push_back(sigma.error * 1e3 / r.lwc_g_m3);
      c.ssa.push_back(albedo.value);
      c.ssa_error.push_back(albedo.error);
      c.rho.push_back(r.rho_g_cm3);
      const std::vector<double> chi = cell_moments(cell, t.max_moment);
      c.nmom.push_back(significant_moments(chi, c.complete));
      for (std::size_t l = 0; l < nmommax; ++l)
        c.pmom.push_back(l < chi.size() ? static_cast<float>((2.0 * l + 1) * chi[l]) : 0.0f);
      c.nth.push_back(static_cast<int>(grid.theta.size()));
      for (double a : grid.theta) c.theta.push_back(static_cast<float>(a));
      for (double p : cell_phase(t, cell, grid)) c.phase.push_back(static_cast<float>(p));
    }
  }
  return c;
}

// The global attributes uvspec reads (version, complete_moments) and those
// that say where the file comes from.
void libradtran_attributes(io::NetcdfFile& f, const SigmaTable& t, const std::vector<Row>& rows,
                           const TableProvenance& provenance, const PhaseGrid& grid, bool complete) {
  const int g = io::NetcdfFile::global;
  f.set_attribute(g, "file_info", "Netcdf file created by " + provenance.producer +
                                      " in the layout of libRadtran's Mie tool (uvspec wc_properties/ic_properties)");
  f.set_int_attribute(g, "version", 20110916);
  f.set_int_attribute(g, "complete_moments", complete ? 1 : 0);
  f.set_attribute(g, "parameterization", "mie");
  std::string distributions;
  for (const Row& r : rows) distributions += (distributions.empty() ? "" : "; ") + t.conditions[r.condition].label;
  f.set_attribute(g, "size_distr", "attenuvis conditions, one per effective radius: " + distributions);
  f.set_attribute(g, "param_alpha", -999.0);
  f.set_attribute(g, "attenuvis_rel_tolerance", t.settings.rel_tolerance);
  f.set_attribute(g, "pmom_convention", "pmom(l) = (2l+1) chi_l, chi_0 = 1, p(mu) = sum pmom(l) P_l(mu)");
  f.set_attribute(g, "phase_source", grid.from_moments ? "sum over the stored moments (as libRadtran's mie tool)"
                                                       : "the bulk phase function at the table's angles");
}

}  // namespace

void detail::write_sigma_table_libradtran(const SigmaTable& t, const std::string& path,
                                          const TableProvenance& provenance) {
  if (t.wavelengths_m.empty() || t.conditions.empty()) throw std::invalid_argument("an empty table has no libradtran form");
  require_moments(t, "libradtran");
  const std::vector<Row> rows = effective_radius_rows(t);
  const PhaseGrid grid = phase_grid(t);
  const std::size_t nlam = t.wavelengths_m.size(), nreff = rows.size();
  const std::size_t nmommax = static_cast<std::size_t>(t.max_moment) + 2, ntheta = grid.theta.size();
  const LibradtranColumns c = libradtran_columns(t, rows, shared_index(t, rows), grid, nmommax);

  io::NetcdfFile f(path, io::NetcdfFile::Format::classic);
  libradtran_attributes(f, t, rows, provenance, grid, c.complete);
  const int dlam = f.add_dimension("nlam", nlam), dmom = f.add_dimension("nmommax", nmommax);
  const int dpha = f.add_dimension("nphamat", 1), dreff = f.add_dimension("nreff", nreff);
  const int dth = f.add_dimension("nthetamax", ntheta);
  f.add_dimension("nrho", 1);
  // Each variable is defined with its long name and units, and written once
  // the definitions end (classic netCDF), in the same order.
  std::vector<std::function<void()>> writes;
  const auto variable = [&](const char* name, const std::vector<int>& dims, const auto& data,
                            const std::string& long_name, const std::string& units) {
    using T = typename std::decay_t<decltype(data)>::value_type;
    int var = -1;
    if constexpr (std::is_same_v<T, double>) var = f.add_double_variable(name, dims);
    else if constexpr (std::is_same_v<T, float>) var = f.add_float_variable(name, dims);
    else {
      static_assert(std::is_same_v<T, int>, "double, float or int columns");
      var = f.add_int_variable(name, dims);
    }
    f.set_attribute(var, "long_name", long_name);
    f.set_attribute(var, "units", units);
    writes.push_back([&f, var, &data] { f.write(var, data); });
    return var;
  };
  variable("wavelen", {dlam}, c.wavelen, "wavelength", "micrometer");
  variable("reff", {dreff}, c.reff, "effective radius", "micrometer");
  variable("ntheta", {dlam, dreff, dpha}, c.nth, "number of scattering angles", "-");
  const int v_theta = variable("theta", {dlam, dreff, dpha, dth}, c.theta, "theta", "degrees");
  f.set_float_attribute(v_theta, "_FillValue", -999.0f);
  const int v_phase = variable("phase", {dlam, dreff, dpha, dth}, c.phase, "phase", "-");
  f.set_float_attribute(v_phase, "_FillValue", -999.0f);
  variable("nmom", {dlam, dreff, dpha}, c.nmom, "number of Legendre polynomials", "-");
  const int v_pmom = variable("pmom", {dlam, dreff, dpha, dmom}, c.pmom, "Legendre polynomials", "including factor 2*l+1");
  f.set_float_attribute(v_pmom, "_FillValue", 0.0f);
  variable("ext", {dlam, dreff}, c.ext, "extinction coefficient", "km^-1/(g/m^3)");
  variable("ssa", {dlam, dreff}, c.ssa, "single scattering albedo", "-");
  variable("refre", {dlam}, c.refre, "refractive index (real)", " ");
  variable("refim", {dlam}, c.refim, "refractive index (imaginary)", " ");
  variable("rho", {dlam, dreff}, c.rho, "density of medium", "g/cm^3");
  variable("lwc", {dreff}, c.lwc, "condensed water content of the condition's drops (ext = sigma_ext / lwc)", "g/m^3");
  variable("ext_error", {dlam, dreff}, c.ext_error, "error estimate of ext (attenuvis)", "km^-1/(g/m^3)");
  variable("ssa_error", {dlam, dreff}, c.ssa_error, "error estimate of ssa (attenuvis)", "-");
  f.end_definitions();
  for (const auto& write : writes) write();
  f.commit();
}

std::string detail::format_sigma_table_disort(const SigmaTable& t, const TableProvenance& provenance,
                                              double layer_thickness_m) {
  if (!(layer_thickness_m > 0) || !std::isfinite(layer_thickness_m))
    throw std::invalid_argument("disort table: the layer thickness must be > 0 m");
  require_moments(t, "disort");
  for (std::size_t c = 0; c < t.conditions.size(); ++c) mie_condition(t, c, "disort");
  std::ostringstream o;
  o << "# DISORT input of one homogeneous layer per row, written by " << provenance.producer << "\n"
    << "# DTAUC = sigma_ext x " << io::shortest(layer_thickness_m) << " m (optical depth of the layer), "
    << "SSALB = sigma_sca / sigma_ext, PMOM(l) = chi_l, l = 0.." << t.max_moment
    << " (PMOM(0) = 1; p(mu) = sum (2l+1) PMOM(l) P_l(mu))\n"
    << "# wavelength_nm condition DTAUC SSALB NMOM PMOM(0) ... PMOM(NMOM)\n";
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      const TableCell& cell = t.at(w, c);
      o << io::shortest(wavelength_nm(t.wavelengths_m[w])) << " " << t.conditions[c].label << " "
        << io::shortest(table_value(cell, Quantity::sigma_ext).value * layer_thickness_m) << " "
        << io::shortest(table_value(cell, Quantity::ssa).value) << " " << t.max_moment;
      for (double chi : cell_moments(cell, t.max_moment)) o << " " << io::shortest(chi);
      o << "\n";
    }
  return o.str();
}

}  // namespace attenuvis::weather
