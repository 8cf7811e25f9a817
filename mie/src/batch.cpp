// Batch evaluation and the text grammar of `attenuvis mie` (see batch.hpp).
#include "attenuvis/mie/batch.hpp"

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/spheres.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace attenuvis::mie::batch {
namespace {

// Whole-token strict number parsing: "1.5x" or "" are errors, not 1.5 or 0.
double parse_number(const std::string& token, const char* what) {
  if (token.empty()) throw std::invalid_argument(std::string("missing ") + what);
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size())
    throw std::invalid_argument(std::string("cannot parse ") + what + " '" + token + "'");
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " '" + token + "' is not finite");
  if (errno == ERANGE && v != 0.0)  // overflow is caught above; underflow to a denormal is fine
    throw std::invalid_argument(std::string(what) + " '" + token + "' is out of range");
  return v;
}

std::vector<std::string> split_fields(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (c == ',' || c == '\t' || c == '\r') c = ' ';
  std::istringstream is(s);
  std::vector<std::string> fields;
  for (std::string f; is >> f;) fields.push_back(f);
  return fields;
}

// %.17g by std::to_chars (the same text as printf's, without its locale and
// format-string machinery).
void append_number(std::string& out, double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17);
  out.append(buf, r.ptr);
}

// The output's own header (all of it, or its first three names "x m_re
// m_im"), so that a CSV written by `attenuvis mie` can be fed back.
bool is_header(const std::vector<std::string>& f) {
  // Today's header, and the one written before qpr and terms were added.
  static const std::vector<std::string> names = {"x", "m_re", "m_im", "qext", "qsca", "qabs", "qback", "qpr", "g", "terms"};
  static const std::vector<std::string> older = {"x", "m_re", "m_im", "qext", "qsca", "qabs", "qback", "g"};
  for (const auto* h : {&names, &older}) {
    if (f.size() != 3 && f.size() != h->size()) continue;
    if (std::equal(f.begin(), f.end(), h->begin())) return true;
  }
  return false;
}

}  // namespace

std::optional<Problem> parse_line(const std::string& line) {
  const std::string content = line.substr(0, line.find('#'));
  const std::vector<std::string> f = split_fields(content);
  if (f.empty()) return std::nullopt;
  if (is_header(f)) return std::nullopt;
  if (f.size() != 3)
    throw std::invalid_argument("expected 3 fields 'x m_re m_im', got " + std::to_string(f.size()));
  Problem p;
  p.x = parse_number(f[0], "x");
  const double n = parse_number(f[1], "m_re");
  const double k = parse_number(f[2], "m_im");
  if (p.x <= 0) throw std::invalid_argument("x must be > 0, got " + f[0]);
  if (k < 0) throw std::invalid_argument("m_im must be >= 0 (k > 0 absorbs), got " + f[2]);
  if (n < 0) throw std::invalid_argument("m_re must be >= 0, got " + f[1]);
  p.m = {n, k};
  return p;
}

const char* csv_header() { return "x,m_re,m_im,qext,qsca,qabs,qback,qpr,g,terms"; }

std::string csv_row(const Problem& p, const Efficiencies<double>& q) {
  std::string row;
  // The input as the shortest text that reads back to it (1.33, not
  // 1.3300000000000001); the results at 17 digits, which read back exactly.
  row += io::shortest(p.x) + ',' + io::shortest(p.m.real()) + ',' + io::shortest(p.m.imag());
  for (double v : {q.qext, q.qsca, q.qabs, q.qback, q.qpr, q.g}) {
    row += ',';
    append_number(row, v);
  }
  row += ',';
  row += std::to_string(q.terms);
  return row;
}

// Good lines are collected in chunks and evaluated together by spheres()
// (several spheres per vector instruction, threads over cores); rows are
// written in input order.  Messages for lines that fail to parse are written
// as they are read, those for lines the core rejects (outside the domain of attenuvis/mie.hpp) when
// their chunk is evaluated.
std::size_t run(std::istream& in, std::ostream& out, std::ostream& err, const Options& options) {
  constexpr std::size_t kChunk = 4096;
  out << csv_header() << '\n';
  std::size_t bad = 0, line_number = 0;
  std::vector<Problem> problems;
  std::vector<std::size_t> line_of;
  std::vector<double> xs;
  std::vector<std::complex<double>> ms;
  std::vector<Efficiencies<double>> q;
  std::string text;
  SpheresOptions spheres_options;
  spheres_options.options = options;
  auto evaluate = [&] {
    const std::size_t n = problems.size();
    xs.resize(n), ms.resize(n), q.resize(n);
    for (std::size_t i = 0; i < n; ++i) xs[i] = problems[i].x, ms[i] = problems[i].m;
    const std::vector<SphereError> errors = spheres(xs.data(), ms.data(), n, q.data(), spheres_options);
    std::size_t e = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (e < errors.size() && errors[e].index == i) {
        ++bad;
        err << "line " << line_of[i] << ": " << errors[e++].message << '\n';
        continue;
      }
      text += csv_row(problems[i], q[i]);
      text += '\n';
    }
    out << text;
    text.clear();
    problems.clear();
    line_of.clear();
  };
  // Lines are cut out of 64 KiB blocks: std::getline on a stream synchronised
  // with C stdio (std::cin by default) reads one character per library call,
  // which took a third of the time of a batch at x = 1.
  std::vector<char> block(std::size_t(1) << 16);
  std::string pending, line;
  std::size_t pos = 0;  // start of the unread part of `pending`
  bool more = true;
  auto next_line = [&]() -> bool {
    for (;;) {
      const auto nl = pending.find('\n', pos);
      if (nl != std::string::npos) {
        line.assign(pending, pos, nl - pos);
        pos = nl + 1;
        return true;
      }
      if (!more) {
        if (pos >= pending.size()) return false;
        line.assign(pending, pos, std::string::npos);  // last line without a newline
        pos = pending.size();
        return true;
      }
      pending.erase(0, pos);
      pos = 0;
      in.read(block.data(), static_cast<std::streamsize>(block.size()));
      const std::streamsize got = in.gcount();
      if (got > 0) pending.append(block.data(), static_cast<std::size_t>(got));
      if (!in) more = false;  // end of input (or a read error): what was read is kept
    }
  };
  while (next_line()) {
    ++line_number;
    try {
      const std::optional<Problem> p = parse_line(line);
      if (!p) continue;
      problems.push_back(*p);
      line_of.push_back(line_number);
      if (problems.size() == kChunk) evaluate();
    } catch (const std::exception& e) {
      ++bad;
      err << "line " << line_number << ": " << e.what() << '\n';
    }
  }
  evaluate();
  return bad;
}

std::complex<double> parse_refractive_index(const std::string& text) {
  const io::IndexText parts = io::split_index_text(text, "refractive index");
  const double n = parse_number(parts.real, "n");
  const double k = parse_number(parts.imag, "k");
  if (n < 0 || k < 0) throw std::invalid_argument("refractive index needs n >= 0 and k >= 0, got '" + text + "'");
  return {n, k};
}

std::vector<double> parse_angles(const std::string& text) {
  std::vector<double> angles;
  if (text.find(':') != std::string::npos) {
    std::string s = text;
    for (char& c : s)
      if (c == ':') c = ' ';
    const std::vector<std::string> f = split_fields(s);
    if (f.size() != 3) throw std::invalid_argument("angles must be 'start:stop:step', got '" + text + "'");
    const double a = parse_number(f[0], "start angle"), b = parse_number(f[1], "stop angle"),
                 step = parse_number(f[2], "angle step");
    if (!(step > 0) || b < a) throw std::invalid_argument("angles need step > 0 and stop >= start, got '" + text + "'");
    const double count = std::floor((b - a) / step + 1e-9);
    if (count > 1e6) throw std::invalid_argument("more than 1e6 angles in '" + text + "'");
    // Rounded to 12 significant digits, so that 0:1:0.1 names 0.3 and not
    // a + 3 step = 0.30000000000000004: every command computes at the angles
    // the grid's text names.
    for (double i = 0; i <= count; ++i) angles.push_back(std::stod(io::significant(a + i * step, 12)));
  } else {
    for (const std::string& f : split_fields(text)) angles.push_back(parse_number(f, "angle"));
    if (angles.empty()) throw std::invalid_argument("no angle in '" + text + "'");
  }
  for (double t : angles)
    if (t < 0 || t > 180) throw std::invalid_argument("scattering angles must lie in [0, 180] degrees");
  return angles;
}

}  // namespace attenuvis::mie::batch
