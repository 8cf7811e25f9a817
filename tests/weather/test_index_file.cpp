// Refractive indices from files (index_file.hpp): refractiveindex.info YAML
// (tabulated and the nine formulas), three columns with their sign rule,
// OPAC's files; and the errors, each naming the file and line.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

const std::string kData = std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/index/";

// A refractiveindex.info file with one formula for n.
std::string formula_file(int type, const std::string& coefficients, const std::string& range) {
  return "# made for this test\nREFERENCES: |\n    a test\nDATA:\n  - type: formula " + std::to_string(type) +
         "\n    wavelength_range: " + range + "\n    coefficients: " + coefficients + "\n";
}

std::string thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("index file: refractiveindex.info tabulated nk reads as the project's own water table",
          "[weather][index]") {
  // H2O-Hale.yml is the database's file the project's water-hale-querry-1973.csv was copied
  // from (data/refractive-index): the same rows and the same interpolation give the same numbers.
  const MaterialIndex yml = read_index_file(kData + "H2O-Hale.yml");
  const RefractiveIndexTable& csv = refractive_index_table("water");
  for (double w : {0.2e-6, 0.355e-6, 0.55e-6, 1.064e-6, 10.6e-6, 200e-6}) {
    INFO(w);  // the rows are in um there and in m here: the same up to rounding of ln(lambda)
    CHECK(yml.at(w).real() == Approx(csv.at(w).real()).epsilon(1e-14));
    CHECK(yml.at(w).imag() == Approx(csv.at(w).imag()).epsilon(1e-13));
  }
  // Hale & Querry 1973, Table 1: 1.333, 1.96e-9 at 0.550 um.
  CHECK(yml.at(0.55e-6).real() == Approx(1.333).epsilon(1e-15));
  CHECK(yml.at(0.55e-6).imag() == Approx(1.96e-9).epsilon(1e-14));
  CHECK(yml.min_wavelength_m() == Approx(0.2e-6));
  CHECK(yml.max_wavelength_m() == Approx(200e-6));
  CHECK_THAT(yml.citation(), Contains("Hale") && Contains("Appl. Opt.") && !Contains("<a"));
  CHECK_THAT(yml.description(), Contains("tabulated nk"));
}

TEST_CASE("index file: the nine formulas of refractiveindex.info", "[weather][index]") {
  // Expected: the formulas as the database documents them (index_file.hpp), evaluated
  // independently in Python (float64) with these coefficients.  Formula 1 holds Malitson's
  // fused silica (J. Opt. Soc. Am. 55, 1205 (1965), Table 1: n = 1.45846 at 0.5875618 um);
  // formula 6 Ciddor's standard air (Appl. Opt. 35, 1566 (1996)), formula 5 oleic acid
  // (Jones et al., Chem. Commun. 51, 4914 (2015)), formula 2 Sultanova's polystyrene.
  struct Case {
    int type;
    const char* coefficients;
    double um, n;
  };
  const Case cases[] = {
      {1, "0 0.6961663 0.0684043 0.4079426 0.1162414 0.8974794 9.896161", 0.5875618, 1.458463687137226},
      {2, "0 1.4435 0.020216", 0.5875618, 1.591630166312466},
      {3, "2.1 0.01 2 -0.012 -2", 0.6, 1.4388421270822824},
      {4, "2.0 0.5 2 0.1 2 0.2 2 10 2 0.001 2", 0.8, 1.5834419039453271},
      {5, "1.4554 4.565E-3 -2 1E-4 -4", 0.55, 1.4715837306194932},
      {6, "0 0.05792105 238.0185 0.00167917 57.362", 0.55, 1.0002778376354293},
      {7, "1.5 0.01 0.001 -0.001 0 0", 0.7, 1.5258400912651562},
      {8, "0.3 0.02 0.01 -0.001", 0.9, 1.5518165089626823},
      {9, "2.2 0.05 0.02 0.1 3.0 0.5", 1.2, 1.4788789420908137},
  };
  for (const Case& c : cases) {
    INFO("formula " << c.type);
    const MaterialIndex m = parse_refractiveindex_yaml(formula_file(c.type, c.coefficients, "0.2 2.0"), "f.yml");
    CHECK(m.at(c.um * 1e-6).real() == Approx(c.n).epsilon(1e-14));
    CHECK(m.at(c.um * 1e-6).imag() == 0);
  }
  const MaterialIndex silica = parse_refractiveindex_yaml(formula_file(1, cases[0].coefficients, "0.21 6.7"), "s.yml");
  CHECK(silica.at(0.5875618e-6).real() == Approx(1.45846).margin(5e-6));  // Malitson's printed digits
}

TEST_CASE("index file: a formula for n with tabulated k, over the range both cover", "[weather][index]") {
  const std::string text =
      "DATA:\n- type: formula 5\n  wavelength_range: 0.4 1.0\n  coefficients: 1.5 0.01 -2\n"
      "- type: tabulated k\n  data: |\n      0.3 1e-3\n      0.6 1e-4\n      0.9 1e-5\n";
  const MaterialIndex m = parse_refractiveindex_yaml(text, "mix.yml");
  CHECK(m.min_wavelength_m() == Approx(0.4e-6));
  CHECK(m.max_wavelength_m() == Approx(0.9e-6));
  // k as a power law in wavelength between 0.6 and 0.9 um: 1e-4 (0.75/0.6)^(ln 0.1 / ln 1.5).
  CHECK(m.at(0.75e-6).imag() == Approx(1e-4 * std::pow(0.75 / 0.6, std::log(0.1) / std::log(1.5))).epsilon(1e-13));
  CHECK(m.at(0.75e-6).real() == Approx(1.5 + 0.01 / (0.75 * 0.75)).epsilon(1e-14));
  CHECK_THAT(thrown([&] { m.at(0.35e-6); }), Contains("350 nm") && Contains("mix.yml") && Contains("0.4 - 0.9 um"));
}

TEST_CASE("index file: three columns, the sign of k stated or detected", "[weather][index]") {
  const std::string positive = "# quartz-like\n0.4 1.55 0.001\n0.6 1.54, 0.002\n0.8\t1.53\t0.003\n";
  const MaterialIndex p = parse_index_columns(positive, "p.txt", ImaginarySign::detect);
  CHECK(p.at(0.6e-6).real() == Approx(1.54).epsilon(1e-15));
  CHECK(p.at(0.6e-6).imag() == Approx(0.002).epsilon(1e-14));
  CHECK_THAT(p.description(), Contains("m = n + ik") && Contains("detected"));
  const std::string negative = "0.4 1.55 -0.001\n0.6 1.54 -0.002\n0.8 1.53 0\n";
  const MaterialIndex n = parse_index_columns(negative, "n.txt", ImaginarySign::detect);
  CHECK(n.at(0.6e-6).imag() == Approx(0.002).epsilon(1e-14));
  CHECK_THAT(n.description(), Contains("m = n - ik"));
  // Stated in the file: a positive k under `# sign: n-ik` is a wrong sign, named with its line.
  CHECK_THAT(thrown([] { parse_index_columns("# sign: n-ik\n0.4 1.5 -0.1\n0.5 1.5 0.1\n", "s.txt", ImaginarySign::detect); }),
             Contains("s.txt:3") && Contains("wrong sign"));
  // Detected: both signs in one file.
  CHECK_THAT(thrown([] { parse_index_columns("0.4 1.5 0.1\n0.5 1.5 -0.1\n", "m.txt", ImaginarySign::detect); }),
             Contains("m.txt:2") && Contains("wrong sign") && Contains("one convention"));
  // Stated by the caller (OPAC: k <= 0) against a file of the other sign.
  CHECK_THAT(thrown([] { parse_index_columns("0.4 1.5 0.1\n0.5 1.5 0.1\n", "o.dat", ImaginarySign::n_minus_ik); }),
             Contains("o.dat:1") && Contains("wrong sign"));
  CHECK_THAT(thrown([] { parse_index_columns("# sign: n+ik\n0.4 1.5 0\n0.5 1.5 0\n", "o.dat", ImaginarySign::n_minus_ik); }),
             Contains("o.dat") && Contains("states m = n + ik"));
}

TEST_CASE("index file: malformed files are refused with the file and line", "[weather][index]") {
  struct Bad {
    const char* text;
    bool yaml;
    const char* where;
    const char* why;
  };
  const Bad bad[] = {
      {"0.4 1.5\n0.5 1.5 0\n", false, "t:1", "2 column(s)"},
      {"0.4 1.5 0 7\n", false, "t:1", "4 columns"},
      {"0.5 1.5 0\n0.4 1.5 0\n", false, "t:2", "does not increase"},
      {"0.4 -1.5 0\n0.5 1.5 0\n", false, "t:1", "must be > 0"},
      {"0.4 1.5 x\n0.5 1.5 0\n", false, "t:1", "not a number"},
      {"0.4 1.5 0\n", false, "t", "at least two"},
      {"DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1.3 -1e-3\n        0.6 1.3 0\n", true, "t:4", "negative"},
      {"DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1.3\n", true, "t:4", "rows have 3"},
      {"DATA:\n  - type: formula 2\n    coefficients: 0 1 0.01\n", true, "t:2", "wavelength_range"},
      {"DATA:\n  - type: formula 2\n    wavelength_range: 0.3 1\n    coefficients: 0 1\n", true, "t:4", "do not fit formula 2"},
      {"DATA:\n  - type: spline\n", true, "t:2", "not tabulated nk"},
      {"DATA:\n\t- type: tabulated n\n", true, "t:2", "tab"},
      {"REFERENCES: x\n", true, "t", "no DATA"},
      {"DATA:\n  - type: tabulated n\n    data: |\n        0.5 1.3\n        0.6 1.3\n  - type: formula 5\n"
       "    wavelength_range: 0.3 1\n    coefficients: 1.5\n",
       true, "t:6", "second item gives n"},
      {"DATA:\n  - type: tabulated k\n    data: |\n        0.5 1e-3\n        0.6 1e-3\n", true, "t:2", "no DATA item gives n"},
      {"DATA:\n  - type: tabulated n\n    data: |\n        0.5 1.3\n        0.6 1.3\n  - type: tabulated k\n"
       "    data: |\n        0.7 1e-3\n        0.8 1e-3\n",
       true, "t:6", "do not overlap"},
  };
  for (const Bad& b : bad) {
    INFO(b.text);
    const std::string what = thrown([&] {
      if (b.yaml) parse_refractiveindex_yaml(b.text, "t");
      else parse_index_columns(b.text, "t", ImaginarySign::detect);
    });
    CHECK_THAT(what, Contains(std::string(b.where) + ":") && Contains(b.why));
  }
  CHECK_THAT(thrown([] { read_index_file("/nonexistent/n.yml"); }), Contains("/nonexistent/n.yml"));
  CHECK_THAT(thrown([] { read_index_file("/dev/zero"); }), Contains("not a regular file"));
}

TEST_CASE("index file: OPAC's files read as m = n + ik", "[weather][index][opac]") {
  // waso70_refr.dat at 0.55 um: 1.414, -2.470E-03 (OPAC's n - ik); the same row as the
  // OPAC optical-property file waso70 prints (ref.real 1.414, ref.imag -2.470E-03).
  const OpacComponentData& waso = opac_component(AerosolComponent::waso);
  CHECK(waso.states[2].rh_percent == 70);
  CHECK(waso.states[2].index.at(0.55e-6).real() == Approx(1.414).epsilon(1e-15));
  CHECK(waso.states[2].index.at(0.55e-6).imag() == Approx(2.470e-3).epsilon(1e-14));
  CHECK_THAT(thrown([&] { waso.states[2].index.at(0.2e-6); }),
             Contains("200 nm") && Contains("waso70_refr.dat") && Contains("0.25 - 40 um"));
}
