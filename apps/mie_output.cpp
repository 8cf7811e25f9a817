// Output of `attenuvis mie` for one sphere (see mie_output.hpp).
#include "mie_output.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "attenuvis/io/number_text.hpp"

namespace attenuvis::cli {
namespace {

// Results at 17 significant digits: they read back to the same double.
std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void print_amplitudes(const mie::Scattering<double>& s) {
  std::cout << "  theta_deg  Re S1  Im S1  Re S2  Im S2\n";
  for (std::size_t i = 0; i < s.angles_deg.size(); ++i)
    std::cout << "  " << io::shortest(s.angles_deg[i]) << "  " << num(s.s1[i].real()) << "  " << num(s.s1[i].imag())
              << "  " << num(s.s2[i].real()) << "  " << num(s.s2[i].imag()) << "\n";
}

void print_matrix(const mie::ScatteringMatrix& f) {
  std::cout << "  scattering matrix (B&H 4.77, unnormalised) and phase function p (integral of p dOmega = 4 pi)\n"
            << "  theta_deg  S11  S12  S33  S34  p\n";
  for (std::size_t i = 0; i < f.angles_deg.size(); ++i)
    std::cout << "  " << io::shortest(f.angles_deg[i]) << "  " << num(f.s11[i]) << "  " << num(f.s12[i]) << "  "
              << num(f.s33[i]) << "  " << num(f.s34[i]) << "  " << num(f.phase[i]) << "\n";
}

void print_moments(const std::vector<double>& chi) {
  std::cout << "  Legendre moments chi_l of p(mu) = sum (2l+1) chi_l P_l(mu) (chi_0 = 1, chi_1 = g; DISORT's PMOM)\n"
            << "  l  chi_l\n";
  for (std::size_t l = 0; l < chi.size(); ++l) std::cout << "  " << l << "  " << num(chi[l]) << "\n";
}

void print_expansion(const mie::ScatteringMatrixExpansion<double>& e) {
  std::cout << "  generalised spherical function expansion (de Rooij & van der Stap 1984; Mishchenko et al. 2002)\n"
            << "  l  alpha1  alpha2  alpha3  alpha4  beta1  beta2\n";
  for (std::size_t l = 0; l < e.alpha1.size(); ++l)
    std::cout << "  " << l << "  " << num(e.alpha1[l]) << "  " << num(e.alpha2[l]) << "  " << num(e.alpha3[l])
              << "  " << num(e.alpha4[l]) << "  " << num(e.beta1[l]) << "  " << num(e.beta2[l]) << "\n";
}

// A JSON number, or null where the value is not finite (JSON has no inf).
nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

// A layered sphere's layers, "x = 5.7119 m = 1.75 + 0.44i; x = ..." (the
// core "perfect conductor").
std::string layers_text(const MieEcho& echo) {
  std::string t;
  for (std::size_t l = 0; l < echo.layer_x.size(); ++l) {
    if (l > 0) t += "; ";
    t += "x = " + io::shortest(echo.layer_x[l]) + " m = ";
    if (echo.conducting_core && l == 0) {
      t += "perfect conductor";
    } else {
      const std::complex<double> m = echo.layer_m[echo.conducting_core ? l - 1 : l];
      t += io::shortest(m.real()) + " + " + io::shortest(m.imag()) + "i";
    }
  }
  return t;
}

void print_mie_text(const MieEcho& echo, const MieResult& r) {
  const auto& q = r.s.q;
  const mie::Lidar lidar = mie::lidar(q);
  // The input echoed as the shortest text that reads back to it.
  if (echo.layer_x.empty())
    std::cout << "Mie sphere  x = " << io::shortest(echo.x) << "  m = " << io::shortest(echo.m.real()) << " + "
              << io::shortest(echo.m.imag()) << "i";
  else
    std::cout << "Mie layered sphere (core first)  " << layers_text(echo)
              << "\n  efficiencies per cross section of the outer radius (x = " << io::shortest(echo.x) << ")";
  if (!echo.size_text.empty()) std::cout << "  (" << echo.size_text << ")";
  std::cout << "\n"
            << "  Qext  = " << num(q.qext) << "\n"
            << "  Qsca  = " << num(q.qsca) << "\n"
            << "  Qabs  = " << num(q.qabs) << "\n"
            << "  Qback = " << num(q.qback) << "   (Bohren-Huffman 4|S1(180)|^2/x^2; BHMIE's is this/4pi)\n"
            << "  Qpr   = " << num(q.qpr) << "\n"
            << "  g     = " << num(q.g) << "\n"
            << "  terms = " << q.terms << " (" << echo.term_rule << ")\n"
            << "  lidar: Qback/4pi = " << num(lidar.backscatter_per_sr) << " per sr, lidar ratio 4pi Qext/Qback = "
            << num(lidar.lidar_ratio_sr) << " sr, linear depolarisation 0 (exactly, for any sphere)\n";
  if (!r.s.angles_deg.empty()) print_amplitudes(r.s);
  if (r.matrix) print_matrix(*r.matrix);
  if (r.moments) print_moments(*r.moments);
  if (r.expansion) print_expansion(*r.expansion);
}

void print_mie_json(const MieEcho& echo, const MieResult& r) {
  const auto& q = r.s.q;
  const mie::Lidar lidar = mie::lidar(q);
  nlohmann::json j = {{"x", echo.x},         {"m", {echo.m.real(), echo.m.imag()}}, {"qext", q.qext},
                      {"qsca", q.qsca},      {"qabs", q.qabs},                      {"qback", q.qback},
                      {"qpr", q.qpr},        {"g", q.g},                            {"terms", q.terms},
                      {"term_rule", echo.term_rule}};
  if (!echo.size_text.empty()) j["size"] = echo.size_text;
  if (!echo.layer_x.empty()) {
    nlohmann::json layers = nlohmann::json::array();
    for (std::size_t l = 0; l < echo.layer_x.size(); ++l) {
      nlohmann::json layer = {{"x", echo.layer_x[l]}};
      if (echo.conducting_core && l == 0) {
        layer["m"] = "perfect conductor";
      } else {
        const std::complex<double> m = echo.layer_m[echo.conducting_core ? l - 1 : l];
        layer["m"] = {m.real(), m.imag()};
      }
      layers.push_back(layer);
    }
    j["layers"] = layers;
    j.erase("m");
  }
  j["lidar"] = {{"backscatter_per_sr", lidar.backscatter_per_sr},
                {"lidar_ratio_sr", finite_or_null(lidar.lidar_ratio_sr)},
                {"linear_depolarisation", lidar.linear_depolarisation}};
  const auto& s = r.s;
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
  if (r.matrix)
    j["scattering_matrix"] = {{"angles_deg", r.matrix->angles_deg}, {"s11", r.matrix->s11}, {"s12", r.matrix->s12},
                              {"s33", r.matrix->s33},               {"s34", r.matrix->s34}, {"phase", r.matrix->phase},
                              {"phase_normalisation", "integral of phase over 4 pi sr = 4 pi"}};
  if (r.moments) j["legendre_moments"] = *r.moments;
  if (r.expansion)
    j["expansion"] = {{"alpha1", r.expansion->alpha1}, {"alpha2", r.expansion->alpha2},
                      {"alpha3", r.expansion->alpha3}, {"alpha4", r.expansion->alpha4},
                      {"beta1", r.expansion->beta1},   {"beta2", r.expansion->beta2}};
  std::cout << j.dump(2) << "\n";
}

}  // namespace attenuvis::cli
