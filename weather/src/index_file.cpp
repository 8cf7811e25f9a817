// Refractive indices from files (index_file.hpp): the index as a function of
// wavelength, the three-column reader and refractiveindex.info's formulas.
// The YAML reader is index_yaml.cpp.
#include "attenuvis/weather/index_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/input_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "index_text.hpp"
#include "wavelength_interpolation.hpp"

namespace attenuvis::weather {

namespace {

// refractiveindex.info's largest files (tabulated nk over thousands of rows) are a few MB.
constexpr std::size_t kMaxIndexFileBytes = 64u << 20;

std::string range_words(double lo_um, double hi_um) {
  return io::significant(lo_um, 6) + " - " + io::significant(hi_um, 6) + " um";
}

}  // namespace

// ---- The index as a function of wavelength --------------------------------------

MaterialIndex::MaterialIndex(std::string source, std::variant<Column, Formula> n, std::vector<Column> k,
                             double lo_um, double hi_um, std::string description, std::string citation)
    : source_(std::move(source)), description_(std::move(description)), citation_(std::move(citation)),
      n_(std::move(n)), k_(std::move(k)), lo_um_(lo_um), hi_um_(hi_um) {
  ATTENUVIS_CHECK(k_.size() <= 1);
  ATTENUVIS_CHECK(lo_um_ > 0 && hi_um_ >= lo_um_);
}

std::complex<double> MaterialIndex::at(double wavelength_m) const {
  const double um = detail::onto_range(wavelength_m * 1e6, lo_um_, hi_um_);
  if (!(um >= lo_um_ && um <= hi_um_))
    throw std::invalid_argument("wavelength " + io::significant(wavelength_m * 1e9, 6) +
                                " nm is outside the refractive index file '" + source_ + "' (" +
                                range_words(lo_um_, hi_um_) + ")");
  double n = 0;
  if (const auto* column = std::get_if<Column>(&n_)) {
    n = detail::linear_in_log_wavelength(column->wavelength_um, column->value, um);
  } else {
    const auto& f = std::get<Formula>(n_);
    const double v = index_formula(f.type, f.coefficients, um);
    if (formula_gives_square(f.type) && !(v > 0))
      throw std::invalid_argument("refractive index file '" + source_ + "': formula " + std::to_string(f.type) +
                                  " gives n^2 = " + io::significant(v, 4) + " <= 0 at " +
                                  io::significant(um, 6) + " um");
    n = formula_gives_square(f.type) ? std::sqrt(v) : v;
  }
  if (!(n > 0) || !std::isfinite(n))
    throw std::invalid_argument("refractive index file '" + source_ + "': n = " + io::significant(n, 4) + " at " +
                                io::significant(um, 6) + " um is not a positive number");
  const double k =
      k_.empty() ? 0.0 : detail::power_law_in_log_wavelength(k_.front().wavelength_um, k_.front().value, um);
  return {n, k};
}

// ---- refractiveindex.info's dispersion formulas ---------------------------------------

bool formula_gives_square(int type) { return type != 5 && type != 6 && type != 7; }

double index_formula(int type, const std::vector<double>& c, double l) {
  const auto C = [&](std::size_t i) { return i <= c.size() ? c[i - 1] : 0.0; };  // C(1) = c[0], absent = 0
  const double l2 = l * l;
  const std::size_t n = c.size();
  double v = C(1);
  switch (type) {
    case 1:
      for (std::size_t i = 2; i + 1 <= n; i += 2) v += C(i) * l2 / (l2 - C(i + 1) * C(i + 1));
      return v + 1;
    case 2:
      for (std::size_t i = 2; i + 1 <= n; i += 2) v += C(i) * l2 / (l2 - C(i + 1));
      return v + 1;
    case 3:
    case 5:
      for (std::size_t i = 2; i + 1 <= n; i += 2) v += C(i) * std::pow(l, C(i + 1));
      return v;
    case 4:
      for (std::size_t i = 2; i <= std::min<std::size_t>(n, 9); i += 4)
        v += C(i) * std::pow(l, C(i + 1)) / (l2 - std::pow(C(i + 2), C(i + 3)));
      for (std::size_t i = 10; i + 1 <= n; i += 2) v += C(i) * std::pow(l, C(i + 1));
      return v;
    case 6:
      for (std::size_t i = 2; i + 1 <= n; i += 2) v += C(i) / (C(i + 1) - 1 / l2);
      return v + 1;
    case 7: {
      const double L = 1 / (l2 - 0.028);
      return v + C(2) * L + C(3) * L * L + C(4) * l2 + C(5) * l2 * l2 + C(6) * l2 * l2 * l2;
    }
    case 8: {
      const double r = C(1) + C(2) * l2 / (l2 - C(3)) + C(4) * l2;
      return (1 + 2 * r) / (1 - r);
    }
    case 9: return C(1) + C(2) / (l2 - C(3)) + C(4) * (l - C(5)) / ((l - C(5)) * (l - C(5)) + C(6));
  }
  throw std::invalid_argument("refractiveindex.info formula " + std::to_string(type) + " is not one of 1..9");
}

// ---- Three columns ----------------------------------------------------------------

namespace {

// "# sign: n+ik" / "# sign: n-ik" (blanks and case free): the file's own statement.
std::optional<ImaginarySign> stated_sign(const std::string& comment) {
  std::string squeezed;
  for (char ch : comment)
    if (!std::isspace(static_cast<unsigned char>(ch))) squeezed += static_cast<char>(std::tolower(ch));
  if (squeezed == "#sign:n+ik") return ImaginarySign::n_plus_ik;
  if (squeezed == "#sign:n-ik") return ImaginarySign::n_minus_ik;
  return std::nullopt;
}

const char* sign_words(ImaginarySign s) {
  return s == ImaginarySign::n_plus_ik ? "m = n + ik (k >= 0)" : "m = n - ik (k <= 0)";
}

// The rows of a three-column file, k as written (its sign not yet read).
struct ColumnRows {
  MaterialIndex::Column n, k;
  std::vector<int> line;                         // the file's line of each row
  std::optional<ImaginarySign> stated;           // from a `# sign:` line
  std::string comments;                          // the other comment lines, for the citation
};

ColumnRows read_column_rows(const std::string& text, const std::string& source) {
  ColumnRows rows;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = source + ":" + std::to_string(line_no);
    const std::string t = detail::trimmed(line);
    if (t.empty()) continue;
    if (t[0] == '#') {
      if (const auto s = stated_sign(t)) {
        if (rows.stated && *rows.stated != *s) throw std::runtime_error(where + ": a second `# sign:` line disagrees");
        rows.stated = s;
      } else if (rows.comments.size() < 2000) {
        rows.comments += (rows.comments.empty() ? "" : " ") + detail::trimmed(t.substr(1));
      }
      continue;
    }
    const std::vector<std::string> f = detail::fields(t);
    if (f.size() < 3)
      throw std::runtime_error(where + ": " + std::to_string(f.size()) +
                               " column(s); an index file has three: wavelength (um), n, k");
    if (f.size() > 3) throw std::runtime_error(where + ": " + std::to_string(f.size()) + " columns; expected three");
    const double w = detail::number(f[0], where, "wavelength");
    const double n = detail::number(f[1], where, "n");
    const double k = detail::number(f[2], where, "k");
    if (!(w > 0)) throw std::runtime_error(where + ": wavelength " + f[0] + " um must be > 0");
    if (!rows.n.wavelength_um.empty() && !(w > rows.n.wavelength_um.back()))
      throw std::runtime_error(where + ": wavelength " + f[0] + " um does not increase on the row before");
    if (!(n > 0)) throw std::runtime_error(where + ": n = " + f[1] + " must be > 0");
    rows.n.wavelength_um.push_back(w);
    rows.n.value.push_back(n);
    rows.k.value.push_back(k);
    rows.line.push_back(line_no);
  }
  if (rows.n.wavelength_um.size() < 2)
    throw std::runtime_error(source + ": " + std::to_string(rows.n.wavelength_um.size()) +
                             " row(s) of wavelength, n, k; an index file needs at least two");
  rows.k.wavelength_um = rows.n.wavelength_um;
  return rows;
}

// The sign rule of a file: stated by the caller, by the file, or read off its k column.
ImaginarySign sign_rule(const ColumnRows& rows, ImaginarySign asked, const std::string& source) {
  if (rows.stated && asked != ImaginarySign::detect && *rows.stated != asked)
    throw std::runtime_error(source + ": the file states " + sign_words(*rows.stated) + ", but it is read as " +
                             sign_words(asked));
  if (asked != ImaginarySign::detect) return asked;
  if (rows.stated) return *rows.stated;
  // Detected: the sign of the first nonzero k; every other must agree (checked by the caller).
  for (double k : rows.k.value)
    if (k != 0) return k > 0 ? ImaginarySign::n_plus_ik : ImaginarySign::n_minus_ik;
  return ImaginarySign::n_plus_ik;
}

}  // namespace

MaterialIndex parse_index_columns(const std::string& text, const std::string& source, ImaginarySign asked) {
  ColumnRows rows = read_column_rows(text, source);
  const ImaginarySign sign = sign_rule(rows, asked, source);
  const bool detected = asked == ImaginarySign::detect && !rows.stated;
  for (std::size_t i = 0; i < rows.k.value.size(); ++i) {
    const double k = rows.k.value[i];
    const bool wrong = sign == ImaginarySign::n_plus_ik ? k < 0 : k > 0;
    if (wrong)
      throw std::runtime_error(source + ":" + std::to_string(rows.line[i]) + ": k = " + io::shortest(k) +
                               " has the wrong sign: the file is read as " + sign_words(sign) +
                               (detected ? " (from its first nonzero k); one file holds one convention"
                                         : (asked == ImaginarySign::detect ? " (its `# sign:` line)" : "")));
    rows.k.value[i] = std::abs(k);
  }
  const double lo = rows.n.wavelength_um.front(), hi = rows.n.wavelength_um.back();
  const std::string description = "three columns (um, n, k), " + range_words(lo, hi) + ", read as " +
                                  sign_words(sign) + (detected ? " (detected)" : "");
  return MaterialIndex(source, rows.n, {rows.k}, lo, hi, description, rows.comments);
}

MaterialIndex read_index_file(const std::string& path) {
  const std::string text = io::read_input_file(path, kMaxIndexFileBytes);
  const auto ends_with = [&](const char* e) {
    const std::string ext = e;
    return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
  };
  if (ends_with(".yml") || ends_with(".yaml")) return parse_refractiveindex_yaml(text, path);
  return parse_index_columns(text, path, ImaginarySign::detect);
}

}  // namespace attenuvis::weather
