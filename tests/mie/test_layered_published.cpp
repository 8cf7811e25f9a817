// layered_sphere() against published and peer values.
//  * The small-particle limit of a coated sphere: its dipole polarisability
//    (Bohren & Huffman 1983, §5.4 "Coated sphere"; with a perfectly
//    conducting core the limit ε₁ → ∞ of the same formula), from which
//    Qabs = 4x Im(A) and Qsca = (8/3) x⁴ |A|² with A = α/(4π b³) (the dipole
//    cross sections of B&H §5.2), to the O(x²) relative accuracy of the
//    dipole limit.
//  * Efficiencies printed by scattnlay's test scripts for two test cases it
//    compares with n-mie 3a (tests/data/mie/layered_scattnlay_nmie.csv, with
//    its sources): six significant digits, within half a unit of the last one.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/mie/layered.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

// A = α/(4π b³) of a sphere of permittivity ε₁ (radius a) in a shell ε₂
// (radius b) in vacuum, f = a³/b³ (B&H §5.4, with ε_m = 1).
cd coated_polarisability(cd e1, cd e2, double f) {
  const cd num = (e2 - 1.0) * (e1 + 2.0 * e2) + f * (e1 - e2) * (1.0 + 2.0 * e2);
  const cd den = (e2 + 2.0) * (e1 + 2.0 * e2) + f * (2.0 * e2 - 2.0) * (e1 - e2);
  return num / den;
}

// The same with ε₁ → ∞ (a perfectly conducting core): divide by ε₁.
cd conducting_core_polarisability(cd e2, double f) {
  return ((e2 - 1.0) + f * (1.0 + 2.0 * e2)) / ((e2 + 2.0) + f * (2.0 * e2 - 2.0));
}

std::vector<double> split_numbers(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string f;
  while (std::getline(ss, f, ';')) v.push_back(std::stod(f));
  return v;
}

// Half a unit of the last of the six significant digits of a printed value.
double half_unit(const std::string& printed) {
  const double v = std::abs(std::stod(printed));
  if (v == 0) return 0;
  return 0.5 * std::pow(10.0, std::floor(std::log10(v)) - 5);
}

}  // namespace

TEST_CASE("small coated spheres follow B&H's coated-sphere polarisability", "[mie][layered][published]") {
  const double x1 = 1e-4;
  for (double f : {0.001, 0.125, 0.5, 0.9}) {
    for (const auto& pair : std::vector<std::pair<cd, cd>>{{{1.75, 0.44}, {1.43, 1e-3}},
                                                          {{1.31, 1e-3}, {1.33, 1e-3}},
                                                          {{10, 10}, {1.5, 0.1}},
                                                          {{1.5, 0.1}, {3, 1}}}) {
      const cd m1 = pair.first, m2 = pair.second;
      const cd A = coated_polarisability(m1 * m1, m2 * m2, f);
      const double x0 = x1 * std::cbrt(f);
      const auto q = mie::layered_sphere({x0, x1}, {m1, m2});
      INFO("f = " << f << ", m1 = " << m1 << ", m2 = " << m2 << ": Qabs " << q.qabs << " vs " << 4 * x1 * A.imag()
                  << ", Qsca " << q.qsca << " vs " << 8.0 / 3.0 * std::pow(x1, 4) * std::norm(A));
      // Dipole limit: relative corrections O(|m|² x²), <= 1e-5 here.
      CHECK(std::abs(q.qabs - 4 * x1 * A.imag()) <= 1e-4 * q.qabs);
      CHECK(std::abs(q.qsca - 8.0 / 3.0 * std::pow(x1, 4) * std::norm(A)) <= 1e-4 * q.qsca);
    }
    const cd A = conducting_core_polarisability(cd(1.5, 0.01) * cd(1.5, 0.01), f);
    const auto q = mie::layered_sphere(mie::PerfectConductor{}, {x1 * std::cbrt(f), x1}, {cd(1.5, 0.01)});
    INFO("conducting core, f = " << f);
    CHECK(std::abs(q.qabs - 4 * x1 * A.imag()) <= 1e-4 * q.qabs);
  }
}

TEST_CASE("scattnlay's n-mie test cases, six digits", "[mie][layered][published]") {
  const std::string path = std::string(ATTENUVIS_TEST_DATA_DIR) + "/mie/layered_scattnlay_nmie.csv";
  std::ifstream in(path);
  REQUIRE(in);
  std::string line;
  bool header = true;
  int rows = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      CHECK(line == "case,x,m_re,m_im,qext,qsca,qabs,qback,albedo");
      header = false;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) f.push_back(field);
    REQUIRE(f.size() == 9);
    const std::vector<double> x = split_numbers(f[1]), re = split_numbers(f[2]), im = split_numbers(f[3]);
    std::vector<cd> m;
    for (std::size_t l = 0; l < re.size(); ++l) m.emplace_back(re[l], im[l]);
    const auto q = mie::layered_sphere(x, m);
    const double got[] = {q.qext, q.qsca, q.qabs, q.qback, q.qsca / q.qext};
    const char* names[] = {"qext", "qsca", "qabs", "qback", "albedo"};
    for (int k = 0; k < 5; ++k) {
      INFO(f[0] << " at x = " << x.back() << ": " << names[k] << " " << got[k] << " printed " << f[4 + k]);
      CHECK(std::abs(got[k] - std::stod(f[4 + k])) <= half_unit(f[4 + k]));
    }
    ++rows;
  }
  CHECK(rows == 201);
}
