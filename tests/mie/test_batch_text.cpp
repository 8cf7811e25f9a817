// The batch grammar's numbers (attenuvis/mie/batch.hpp): the fast readers and
// writers give the text of the C library's definitions, which are the
// references here — strtod for reading a field, printf's "%.17g" for a result
// and the shortest round-trip text (std::to_chars) for the echoed input.
#include <catch2/catch.hpp>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "attenuvis/mie/batch.hpp"

namespace {

namespace batch = attenuvis::mie::batch;

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Doubles over the whole exponent range, subnormals and powers of ten
// included, in several spellings.
std::vector<std::string> number_texts() {
  std::mt19937_64 rng(20261124);
  std::vector<std::string> texts = {"0",      "-0",     "0.0",     "0e-999",  "1",     "1.",      ".5",
                                    "1e-8",   "1E-08",  "+1.33",   "1.33e0",  "1e308", "1.8e308", "4.9e-324",
                                    "2.2250738585072014e-308", "2.2250738585072009e-308", "1e-400", "0x1.8p1",
                                    "inf",    "nan",    "1e",      "1.5x",    "-1e-8",  "9.999999999999999e22"};
  char buf[64];
  for (int i = 0; i < 20000; ++i) {
    const double v = std::ldexp(std::uniform_real_distribution<double>(0.5, 1.0)(rng),
                                std::uniform_int_distribution<int>(-1074, 1024)(rng));
    texts.emplace_back(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    std::snprintf(buf, sizeof buf, "%.17g", v);
    texts.emplace_back(buf);
    std::snprintf(buf, sizeof buf, "%.3e", v);
    texts.emplace_back(buf);
  }
  return texts;
}

}  // namespace

TEST_CASE("batch lines read each number as strtod reads the whole field", "[mie][batch]") {
  for (const std::string& t : number_texts()) {
    errno = 0;
    char* end = nullptr;
    const double ref = std::strtod(t.c_str(), &end);
    const bool ref_ok = end == t.c_str() + t.size() && std::isfinite(ref) && !(errno == ERANGE && ref != 0.0);
    // The number as m_im (x and m_re fixed), where every value >= 0 is legal.
    bool ok = true;
    double got = 0;
    try {
      got = batch::parse_line("1 1.33 " + t)->m.imag();
    } catch (const std::invalid_argument&) {
      ok = false;
    }
    INFO("field '" << t << "'");
    if (ref_ok && ref >= 0) {
      REQUIRE(ok);
      REQUIRE(bits(got) == bits(ref));
    } else {
      REQUIRE(!ok);
    }
  }
}

TEST_CASE("batch rows: inputs as shortest round-trip text, results as printf's %.17g", "[mie][batch]") {
  std::mt19937_64 rng(42);
  char buf[64];
  for (int i = 0; i < 20000; ++i) {
    const auto any = [&] {
      return std::ldexp(std::uniform_real_distribution<double>(-1.0, 1.0)(rng),
                        std::uniform_int_distribution<int>(-1074, 1024)(rng));
    };
    batch::Problem p;
    p.x = std::abs(any());
    p.m = {std::abs(any()), i % 3 ? std::abs(any()) : 0.0};
    attenuvis::mie::Efficiencies<double> q;
    q.qext = any(), q.qsca = any(), q.qabs = any(), q.qback = any(), q.qpr = any(), q.g = any();
    q.terms = static_cast<std::size_t>(i) * 977u;
    std::ostringstream expected;
    for (const double v : {p.x, p.m.real(), p.m.imag()})
      expected << std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr) << ',';
    for (const double v : {q.qext, q.qsca, q.qabs, q.qback, q.qpr, q.g}) {
      std::snprintf(buf, sizeof buf, "%.17g", v);
      expected << buf << ',';
    }
    expected << q.terms;
    REQUIRE(batch::csv_row(p, q) == expected.str());
  }
}

TEST_CASE("batch run: an index repeated over lines is read and written as on its own", "[mie][batch]") {
  // Same value in other spellings, -0 next to 0, and a bad field that must
  // not take the previous line's value.
  const std::string lines[] = {"1 1.33 0", "2 1.33 -0", "3 1.330 0.0", "4 1.33 0", "5 1.33 0x",
                               "6 1.33 1e-8", "7 1.33 1e-08", "8 1.5 1e-8", "9 1.33 -0"};
  std::string all;
  std::ostringstream expected;
  expected << batch::csv_header() << '\n';
  for (const std::string& l : lines) {
    all += l + '\n';
    std::istringstream one(l + '\n');
    std::ostringstream out, err;
    batch::run(one, out, err);
    expected << out.str().substr(out.str().find('\n') + 1);
  }
  std::istringstream in(all);
  std::ostringstream out, err;
  REQUIRE(batch::run(in, out, err) == 1);
  CHECK(out.str() == expected.str());
  CHECK(err.str() == "line 5: cannot parse m_im '0x'\n");
}
