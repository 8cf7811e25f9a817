// End-to-end tests of `attenuvis mie` (the program at ATTENUVIS_CLI), run
// through the shell with popen.  Expected numbers come from the library
// itself (attenuvis::mie::sphere): these tests check the command's plumbing —
// arguments, formats, 17-digit round trip, batch error handling, exit status.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "attenuvis/mie.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/batch.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"

namespace {

namespace mie = attenuvis::mie;

struct Run {
  int status = -1;
  std::string out, err;
};

std::string temp_path(const std::string& tag) {
  return std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/attenuvis_mie_cli_" + tag + "_" +
         std::to_string(::getpid());
}

// Runs `attenuvis <args>` with `input` on stdin; captures stdout and stderr.
Run run_cli(const std::string& args, const std::string& input = "") {
  const std::string in_path = temp_path("in"), err_path = temp_path("err");
  std::ofstream(in_path) << input;
  const std::string cmd = std::string("'") + ATTENUVIS_CLI + "' " + args + " < '" + in_path + "' 2> '" + err_path + "'";
  Run r;
  FILE* p = ::popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_path);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::remove(in_path.c_str());
  std::remove(err_path.c_str());
  return r;
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream is(s);
  for (std::string l; std::getline(is, l);) v.push_back(l);
  return v;
}

std::vector<double> csv_numbers(const std::string& line) {
  std::vector<double> v;
  std::istringstream is(line);
  for (std::string f; std::getline(is, f, ',');) v.push_back(std::stod(f));
  return v;
}

}  // namespace

TEST_CASE("mie --x --m prints the efficiencies readably", "[mie][cli]") {
  const Run r = run_cli("mie --x 100 --m 1.33,1e-8");
  REQUIRE(r.status == 0);
  const auto q = mie::sphere(100, {1.33, 1e-8});
  char expect[64];
  std::snprintf(expect, sizeof expect, "Qext  = %.17g", q.qext);
  CHECK_THAT(r.out, Catch::Contains(expect));
  for (const char* name : {"Qsca", "Qabs", "Qback", "Qpr", "g ", "terms"}) CHECK_THAT(r.out, Catch::Contains(name));
}

TEST_CASE("mie --json --angles gives the values and S1, S2 arrays", "[mie][cli]") {
  const Run r = run_cli("mie --x 5 --m 1.5,0.1 --angles 0:180:1 --json");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  mie::Extras extras;
  extras.angles_deg = {0.0, 90.0, 180.0};
  const auto s = mie::scatter(5, {1.5, 0.1}, extras);
  CHECK(j.at("qext").get<double>() == s.q.qext);  // JSON numbers round-trip
  CHECK(j.at("qback").get<double>() == s.q.qback);
  CHECK(j.at("g").get<double>() == s.q.g);
  REQUIRE(j.at("angles_deg").size() == 181);
  REQUIRE(j.at("s1").size() == 181);
  REQUIRE(j.at("s2").size() == 181);
  CHECK(j["s1"][90][0].get<double>() == s.s1[1].real());
  CHECK(j["s2"][180][1].get<double>() == s.s2[2].imag());
}

TEST_CASE("mie batch: CSV with 17 digits, comments, commas, bad lines reported, rest computed", "[mie][cli]") {
  const std::string input =
      "# x m_re m_im\n"
      "100 1.33 1e-8\n"
      "\n"
      "1, 1.5, 0   # commas and a trailing comment\n"
      "abc 1.5 0\n"
      "-1 1.5 0\n"
      "1 1.5 -0.1\n"
      "1 inf 0\n"
      "1 1.5\n"
      "0.001\t1.5\t0.1\n";
  const Run r = run_cli("mie", input);
  CHECK(r.status != 0);
  const auto out = lines(r.out);
  REQUIRE(out.size() == 4);
  CHECK(out[0] == "x,m_re,m_im,qext,qsca,qabs,qback,qpr,g,terms");
  const double xs[3] = {100, 1, 0.001};
  const std::complex<double> ms[3] = {{1.33, 1e-8}, {1.5, 0}, {1.5, 0.1}};
  for (int i = 0; i < 3; ++i) {
    const auto v = csv_numbers(out[i + 1]);
    REQUIRE(v.size() == 10);
    const auto q = mie::sphere(xs[i], ms[i]);
    CHECK(v[0] == xs[i]);
    CHECK(v[3] == q.qext);  // %.17g round-trips exactly
    CHECK(v[4] == q.qsca);
    CHECK(v[5] == q.qabs);
    CHECK(v[6] == q.qback);
    CHECK(v[7] == q.qpr);
    CHECK(v[8] == q.g);
    CHECK(v[9] == static_cast<double>(q.terms));  // the same columns as the single-sphere output
  }
  for (const char* where : {"line 5:", "line 6:", "line 7:", "line 8:", "line 9:"})
    CHECK_THAT(r.err, Catch::Contains(where));
  CHECK(lines(r.err).size() == 5);
}

TEST_CASE("mie batch: all good input exits 0, empty input gives just the header", "[mie][cli]") {
  const Run good = run_cli("mie", "2 1.5 0.01\n");
  CHECK(good.status == 0);
  CHECK(lines(good.out).size() == 2);
  CHECK(good.err.empty());
  const Run empty = run_cli("mie", "");
  CHECK(empty.status == 0);
  CHECK(lines(empty.out).size() == 1);
}

TEST_CASE("mie single mode: bad arguments give an error and non-zero exit", "[mie][cli]") {
  for (const char* args : {"mie --x -1 --m 1.5,0", "mie --x 1 --m 1.5,-1", "mie --x 1 --m abc",
                           "mie --x 1 --m 1.5 --angles 0:200:1", "mie --x 1 --terms sometimes"}) {
    const Run r = run_cli(args);
    INFO(args << " -> " << r.err);
    CHECK(r.status != 0);
    CHECK(!r.err.empty());
  }
}

TEST_CASE("mie batch: error lines start with 'attenuvis: error:', its own header is skipped", "[mie][cli]") {
  const Run r = run_cli("mie", "x,m_re,m_im,qext,qsca,qabs,qback,g\n2 1.5 0.01\nabc 1 0\nx m_re m_im\n1 2 0\n");
  CHECK(r.status != 0);
  CHECK(lines(r.out).size() == 3);  // header + two rows
  const auto err = lines(r.err);
  REQUIRE(err.size() == 1);
  CHECK(err[0].rfind("attenuvis: error: line 3: ", 0) == 0);
  // A header alone is not an error.
  const Run header = run_cli("mie", std::string(mie::batch::csv_header()) + "\n");
  CHECK(header.status == 0);
  CHECK(header.err.empty());
}

TEST_CASE("mie batch: the fuzzer's regression lines are errors, not NaN rows", "[mie][cli][domain]") {
  // fuzz/regressions/mie_line/: x below 1e-8, |m| of 1e154 or 1e172, |m| of 1e-300.
  const Run r = run_cli("mie", "1 1e172 0\n1e-200 1.5 0.1\n1e4 1e154 0\n1 1e-300 0\n");
  CHECK(r.status != 0);
  CHECK(lines(r.out).size() == 1);  // the header only
  const auto err = lines(r.err);
  REQUIRE(err.size() == 4);
  for (std::size_t i = 0; i < err.size(); ++i) {
    INFO(err[i]);
    CHECK(err[i].rfind("attenuvis: error: line " + std::to_string(i + 1) + ": mie: ", 0) == 0);
    CHECK_THAT(err[i], Catch::Contains("must") || Catch::Contains("needs"));
  }
}

TEST_CASE("attenuvis --version names the version, commit, build type, Embree, Boost and the data directory",
          "[cli]") {
  const Run r = run_cli("--version");
  CHECK(r.status == 0);
  CHECK(r.err.empty());
  const std::vector<std::string> v = lines(r.out);
  REQUIRE(v.size() == 6);
  CHECK(v[0].rfind("attenuvis ", 0) == 0);
  CHECK(v[0].size() > std::string("attenuvis ").size());  // a version follows the name
  const auto value = [&](std::size_t i, const std::string& key) {
    REQUIRE(v[i].rfind(key, 0) == 0);
    return v[i].substr(v[i].find_first_not_of(' ', key.size()));
  };
  // A short hash (hex digits) from git, or "unknown" for a tree outside a checkout.
  const std::string commit = value(1, "commit:");
  const std::string hash = commit.substr(0, commit.find(' '));
  CHECK((hash == "unknown" || (hash.size() >= 7 && hash.find_first_not_of("0123456789abcdef") == std::string::npos)));
  CHECK(!value(2, "build type:").empty());
  // Embree 3 (the project's find_package floor) and Boost 1.x, as MAJOR.MINOR.PATCH.
  CHECK(value(3, "Embree:").rfind("3.", 0) == 0);
  CHECK(value(4, "Boost:").rfind("1.", 0) == 0);
  CHECK(std::filesystem::is_directory(value(5, "data:") + "/refractive-index"));
}

TEST_CASE("mie --m takes n+ki, n,k and a bare n", "[mie][cli]") {
  const Run comma = run_cli("mie --x 5 --m 1.5,0.1 --json");
  const Run plus = run_cli("mie --x 5 --m 1.5+0.1i --json");
  REQUIRE(comma.status == 0);
  REQUIRE(plus.status == 0);
  CHECK(plus.out == comma.out);
  CHECK(nlohmann::json::parse(plus.out)["m"] == nlohmann::json::array({1.5, 0.1}));
  const Run bare = run_cli("mie --x 5 --m 1.5 --json");
  REQUIRE(bare.status == 0);
  CHECK(nlohmann::json::parse(bare.out)["m"] == nlohmann::json::array({1.5, 0.0}));
  CHECK(mie::batch::parse_refractive_index("1.33-0i") == std::complex<double>(1.33, 0.0));
  for (const char* bad : {"1.5-0.1i", "1.5+i", "1.5,0.1,0", "i", ""}) {
    INFO(bad);
    CHECK_THROWS_AS(mie::batch::parse_refractive_index(bad), std::invalid_argument);
  }
}

TEST_CASE("mie echoes its inputs as the shortest text that reads back, results at 17 digits", "[mie][cli]") {
  // 1.33 and 0.1 print as 1.3300000000000001 and 0.10000000000000001 at 17 digits.
  const Run text = run_cli("mie --x 0.1 --m 1.33,1e-8");
  REQUIRE(text.status == 0);
  CHECK_THAT(text.out, Catch::Contains("x = 0.1  m = 1.33 + 1e-08i"));
  const Run batch = run_cli("mie", "0.1 1.33 0.001\n");
  REQUIRE(batch.status == 0);
  const std::vector<std::string> v = lines(batch.out);
  REQUIRE(v.size() == 2);
  CHECK(v[1].rfind("0.1,1.33,0.001,", 0) == 0);
  const std::vector<double> row = csv_numbers(v[1]);
  REQUIRE(row.size() == 10);
  CHECK(row[3] == mie::sphere(0.1, {1.33, 0.001}).qext);  // the result still reads back exactly
}

TEST_CASE("mie --angles: a request of minutes is refused before it runs", "[mie][cli]") {
  // 1e6 angles at x = 1e4 (about 1e4 terms each): 1e10 amplitude terms.
  const Run big = run_cli("mie --x 1e4 --m 1.33 --angles 0:180:0.00018");
  CHECK(big.status != 0);
  CHECK(big.out.empty());
  CHECK_THAT(big.err, Catch::Contains("attenuvis: error:") && Catch::Contains("1000001 angles") &&
                          Catch::Contains("coarser step"));
  // The same grid at x = 1 (a few terms) is affordable.
  CHECK(run_cli("mie --x 1 --m 1.33 --angles 0:180:0.018").status == 0);
}

TEST_CASE("mie --radius --wavelength --medium-index: x = 2 pi n r / lambda and m / n, as --x would give", "[mie][cli]") {
  const Run by_size = run_cli("mie --radius 5um --wavelength 550nm --medium-index 1.33 --m 1.5+0.01i --json");
  REQUIRE(by_size.status == 0);
  const auto j = nlohmann::json::parse(by_size.out);
  const double x = 2 * M_PI * 1.33 * 5e-6 / 550e-9;
  const std::complex<double> m = std::complex<double>(1.5, 0.01) / 1.33;
  CHECK(j["x"].get<double>() == Approx(x).epsilon(1e-15));
  CHECK(j["m"][0].get<double>() == Approx(m.real()).epsilon(1e-15));
  const auto q = mie::sphere(j["x"].get<double>(), {j["m"][0].get<double>(), j["m"][1].get<double>()});
  CHECK(j["qext"].get<double>() == q.qext);
  CHECK_THAT(j["size"].get<std::string>(), Catch::Contains("radius 5um") && Catch::Contains("wavelength 550nm"));
  // Either --x or the pair; half a pair, or both, is an error naming the options.
  for (const char* bad : {"mie --x 3 --radius 1um --wavelength 1um", "mie --radius 1um", "mie --wavelength 1um",
                          "mie --x 3 --medium-index 1.33", "mie --radius 1 --wavelength 1um",
                          "mie --radius 1um --wavelength 1um --medium-index -1"}) {
    const Run r = run_cli(bad);
    CHECK(r.status != 0);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::StartsWith("attenuvis: error:"));
  }
}

TEST_CASE("mie --phase, --moments, --polarised print what the library computes", "[mie][cli]") {
  const Run r = run_cli("mie --x 5 --m 1.33+0.001i --phase 0:180:30 --moments 12 --polarised --json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  const auto f = mie::scattering_matrix(5, {1.33, 0.001}, {0, 30, 60, 90, 120, 150, 180});
  const auto& sm = j["scattering_matrix"];
  REQUIRE(sm["phase"].size() == 7);
  for (std::size_t i = 0; i < 7; ++i) {
    CHECK(sm["s11"][i].get<double>() == f.s11[i]);
    CHECK(sm["s34"][i].get<double>() == f.s34[i]);
    CHECK(sm["phase"][i].get<double>() == f.phase[i]);
  }
  const auto chi = mie::phase_function_moments(5, {1.33, 0.001}, 12);
  REQUIRE(j["legendre_moments"].size() == 13);
  for (std::size_t l = 0; l <= 12; ++l) CHECK(j["legendre_moments"][l].get<double>() == chi[l]);
  // chi_1 is g (legendre_moments.hpp), here from two different sums.
  CHECK(j["legendre_moments"][1].get<double>() == Approx(j["g"].get<double>()).margin(1e-14));
  REQUIRE(j["expansion"]["alpha1"].size() == 13);
  CHECK(j["expansion"]["alpha1"][2].get<double>() == Approx(5 * chi[2]).margin(1e-13));
  // A sphere does not depolarise (scattering_matrix.hpp): exactly 0.
  CHECK(j["lidar"]["linear_depolarisation"].get<double>() == 0.0);
  CHECK(j["lidar"]["lidar_ratio_sr"].get<double>() ==
        Approx(4 * M_PI * j["qext"].get<double>() / j["qback"].get<double>()).epsilon(1e-15));
  // In batch mode they have no sphere to apply to.
  const Run batch = run_cli("mie --moments 4", "1 1.33 0\n");
  CHECK(batch.status != 0);
  CHECK_THAT(batch.err, Catch::Contains("--moments needs one sphere"));
}

TEST_CASE("mie --layers and --x-layers: a layered sphere, its layers echoed", "[mie][cli][layered]") {
  // Soot (r = 0.5 um) under sulphate (r = 1 um) at 550 nm in air.
  const Run r = run_cli("mie --layers 0.5:1.75+0.44i,1.0:1.43+1e-8i --wavelength 550nm --json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  const double x0 = 2 * M_PI * 0.5e-6 / 550e-9, x1 = 2 * M_PI * 1e-6 / 550e-9;
  REQUIRE(j["layers"].size() == 2);
  CHECK(j["layers"][0]["x"].get<double>() == x0);
  CHECK(j["layers"][1]["m"][1].get<double>() == 1e-8);
  const auto q = mie::layered_sphere({x0, x1}, {{1.75, 0.44}, {1.43, 1e-8}});
  CHECK(j["qext"].get<double>() == q.qext);
  CHECK(j["qback"].get<double>() == q.qback);
  CHECK(j["g"].get<double>() == q.g);
  // The same particle by size parameters, and a radius with its unit.
  const Run by_x = run_cli("mie --x-layers " + attenuvis::io::shortest(x0) + ":1.75+0.44i," +
                           attenuvis::io::shortest(x1) + ":1.43+1e-8i --json");
  REQUIRE(by_x.status == 0);
  CHECK(nlohmann::json::parse(by_x.out)["qext"].get<double>() == q.qext);
  const Run with_unit = run_cli("mie --layers 500nm:1.75+0.44i,1um:1.43+1e-8i --wavelength 550nm --json");
  REQUIRE(with_unit.status == 0);
  CHECK(nlohmann::json::parse(with_unit.out)["qext"].get<double>() == q.qext);
  // Text output with the phase function and moments from the layered coefficients.
  const Run text = run_cli("mie --x-layers 2:pec,3:1.5 --phase 0:180:90 --moments 2");
  REQUIRE(text.status == 0);
  CHECK_THAT(text.out, Catch::Contains("perfect conductor"));
  CHECK_THAT(text.out, Catch::Contains("Legendre moments"));
}

TEST_CASE("mie --layers: bad layers give an error naming the layer", "[mie][cli][layered]") {
  for (const char* args : {"mie --layers 0.5:1.75+0.44i,1.0 --wavelength 550nm",
                           "mie --layers 0.5:1.75,0.44 --wavelength 550nm",
                           "mie --layers 0.5:1.75+0.44i,0.4:1.5 --wavelength 550nm",
                           "mie --layers 0.5:1.75+0.44i,1:pec --wavelength 550nm",
                           "mie --layers 0.5:1.75+0.44i",
                           "mie --x-layers 1:1.5,2:1.33 --m 1.5",
                           "mie --x-layers 1:1.5,abc:1.33"}) {
    INFO(args);
    const Run r = run_cli(args);
    CHECK(r.status != 0);
    CHECK_THAT(r.err, Catch::StartsWith("attenuvis: error: "));
    CHECK(r.out.empty());
  }
  CHECK_THAT(run_cli("mie --layers 0.5:1.75+0.44i,0.4:1.5 --wavelength 550nm").err, Catch::Contains("layer 1"));
}

TEST_CASE("mie batch: layered lines among homogeneous ones, in order, bad ones reported", "[mie][cli][layered]") {
  const std::string input =
      "1 1.5 0\n"
      "5.71;11.42 1.75;1.43 0.44;1e-8   # soot under sulphate\n"
      "1;2;3 1.5;1.33;2 0.1;0;0.001\n"
      "1;2 1.5;1.33 0.1\n"
      "2;1 1.5;1.5 0;0\n"
      "1;2 1.5; 0;0\n"
      "2 1.33 0\n";
  const Run r = run_cli("mie", input);
  CHECK(r.status != 0);
  const auto out = lines(r.out);
  REQUIRE(out.size() == 5);
  CHECK(out[2].rfind("5.71;11.42,1.75;1.43,0.44;1e-08,", 0) == 0);
  std::istringstream row(out[2]);
  std::vector<std::string> f;
  for (std::string s; std::getline(row, s, ',');) f.push_back(s);
  REQUIRE(f.size() == 10);
  CHECK(std::stod(f[3]) == mie::layered_sphere({5.71, 11.42}, {{1.75, 0.44}, {1.43, 1e-8}}).qext);
  CHECK(std::stod(f[8]) == mie::layered_sphere({5.71, 11.42}, {{1.75, 0.44}, {1.43, 1e-8}}).g);
  CHECK(out[3].rfind("1;2;3,", 0) == 0);
  CHECK(csv_numbers(out[4])[0] == 2);
  for (const char* where : {"line 4:", "line 5: mie: layer 1", "line 6:"}) CHECK_THAT(r.err, Catch::Contains(where));
  CHECK(lines(r.err).size() == 3);
}
