// CSV size-distribution reader with line-numbered validation.
#include "attenuvis/weather/distribution_file.hpp"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "attenuvis/io/input_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/domains.hpp"

namespace attenuvis::weather {
namespace {

// A size distribution has at most a few thousand rows of two or three numbers.
constexpr std::size_t kMaxDistributionFileBytes = 16u << 20;
constexpr std::size_t kMaxDistributionLineChars = 4096;

std::string trim(const std::string& s) {
  auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// The cells between commas, trimmed; a trailing comma ends an empty cell.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = line.find(',', begin);
    out.push_back(trim(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin)));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return out;
}

// Metres per radius unit in a column name ending in _um, _m or _mm.
double radius_scale(const std::string& col, const std::string& stem, bool& ok) {
  ok = true;
  if (col == stem + "_um") return 1e-6;
  if (col == stem + "_mm") return 1e-3;
  if (col == stem + "_m") return 1.0;
  ok = false;
  return 0;
}

[[noreturn]] void fail(const std::string& source, int line, const std::string& what) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

const char* distribution_file_format() {
  return "size-distribution CSV: '#' comments, then a header naming units, then rows:\n"
         "  radius_um,dNdr_per_cm3_per_um      (radius_m|radius_mm; dNdr_per_m3_per_m)  points, >= 2\n"
         "  radius_um,dNdlnr_per_cm3           (dNdlnr_per_m3)                          points, >= 2\n"
         "  radius_lo_um,radius_hi_um,count_per_cm3   (_m|_mm; count_per_m3)            bins, >= 1";
}

SizeDistribution read_distribution_csv(const std::string& path) {
  std::string text;
  try {
    text = io::read_input_file(path, kMaxDistributionFileBytes);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(std::string("size-distribution file ") + e.what());
  }
  std::istringstream in(std::move(text));
  return read_distribution_csv(in, path);
}

namespace {

enum class Kind { dndr, dndlnr, bins };

// What a header states: the kind of table and the factor that takes each
// column to SI (radii in m, densities in m^-4, counts in m^-3).
struct Columns {
  Kind kind = Kind::dndr;
  double r_scale = 0, r2_scale = 0, n_scale = 0;
};

// Nothing when the header does not state the columns and their units.
std::optional<Columns> read_header(const std::vector<std::string>& cells) {
  Columns c;
  bool ok1 = false, ok2 = false;
  if (cells.size() == 2) {
    c.r_scale = radius_scale(cells[0], "radius", ok1);
    if (cells[1] == "dNdr_per_cm3_per_um") { c.kind = Kind::dndr; c.n_scale = 1e12; ok2 = true; }
    else if (cells[1] == "dNdr_per_m3_per_m") { c.kind = Kind::dndr; c.n_scale = 1; ok2 = true; }
    else if (cells[1] == "dNdlnr_per_cm3") { c.kind = Kind::dndlnr; c.n_scale = 1e6; ok2 = true; }
    else if (cells[1] == "dNdlnr_per_m3") { c.kind = Kind::dndlnr; c.n_scale = 1; ok2 = true; }
  } else if (cells.size() == 3) {
    c.kind = Kind::bins;
    bool ok3 = false;
    c.r_scale = radius_scale(cells[0], "radius_lo", ok1);
    c.r2_scale = radius_scale(cells[1], "radius_hi", ok3);
    ok1 = ok1 && ok3;
    if (cells[2] == "count_per_cm3") { c.n_scale = 1e6; ok2 = true; }
    else if (cells[2] == "count_per_m3") { c.n_scale = 1; ok2 = true; }
  }
  if (!ok1 || !ok2) return std::nullopt;
  return c;
}

// The rows after the header, checked one by one, into the segments of a
// piecewise-linear n(r).
class Rows {
 public:
  Rows(const std::string& source, const Columns& columns) : source_(source), c_(columns) {}

  void add(int line_no, const std::vector<std::string>& cells) {
    std::size_t want = c_.kind == Kind::bins ? 3 : 2;
    if (cells.size() != want)
      fail(source_, line_no, "expected " + std::to_string(want) + " comma-separated values, found " +
                                 std::to_string(cells.size()));
    // The labels are constants: a table may hold a million rows.
    static constexpr std::string_view kColumn[3] = {"column 1", "column 2", "column 3"};
    std::vector<double> v;
    v.reserve(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) {
      try {
        v.push_back(io::parse_double(cells[i], kColumn[i]));
      } catch (const std::invalid_argument& e) {
        fail(source_, line_no, e.what());
      }
    }
    if (c_.kind == Kind::bins) add_bin(line_no, cells, v);
    else add_point(line_no, cells, v);
  }

  SizeDistribution finish() {
    if (c_.kind != Kind::bins) {
      if (points_.size() < 2)
        throw std::invalid_argument(source_ + ": a point table needs at least 2 rows (found " +
                                    std::to_string(points_.size()) + "); for a single size use one bin " +
                                    "(radius_lo_um,radius_hi_um,count_per_cm3)");
      for (std::size_t i = 0; i + 1 < points_.size(); ++i)
        segments_.push_back({points_[i].first, points_[i + 1].first, points_[i].second, points_[i + 1].second});
    }
    if (segments_.empty()) throw std::invalid_argument(source_ + ": no bins after the header");
    auto d = SizeDistribution::tabulated(std::move(segments_), source_);
    if (!(d.moment(0) > 0)) throw std::invalid_argument(source_ + ": the distribution holds no particles (all zero)");
    return d;
  }

 private:
  // Each value within its domain (domains.hpp), checked in SI.
  void in_range(int line_no, const std::vector<std::string>& cells, const Domain& range, double si,
                std::size_t column) const {
    try {
      require_in_si(range, si);
    } catch (const std::invalid_argument& e) {
      fail(source_, line_no, "column " + std::to_string(column + 1) + " (" + quote_text(cells[column]) + "): " + e.what());
    }
  }

  void add_bin(int line_no, const std::vector<std::string>& cells, const std::vector<double>& v) {
    double lo = v[0] * c_.r_scale, hi = v[1] * c_.r2_scale, count = v[2] * c_.n_scale;
    if (count < 0) fail(source_, line_no, "negative count");
    in_range(line_no, cells, domain::drop_radius, lo, 0);
    in_range(line_no, cells, domain::drop_radius, hi, 1);
    in_range(line_no, cells, domain::number_per_volume, count, 2);
    if (!(hi > lo)) fail(source_, line_no, "bin upper radius must exceed its lower radius");
    if (!segments_.empty() && lo < segments_.back().r1)
      fail(source_, line_no, "bins must increase and not overlap (lower radius below the previous bin's upper)");
    double n = count / (hi - lo);
    segments_.push_back({lo, hi, n, n});
  }

  void add_point(int line_no, const std::vector<std::string>& cells, const std::vector<double>& v) {
    double r = v[0] * c_.r_scale, n = v[1] * c_.n_scale;
    if (n < 0) fail(source_, line_no, "negative density");
    in_range(line_no, cells, domain::drop_radius, r, 0);
    in_range(line_no, cells, c_.kind == Kind::dndlnr ? domain::number_per_volume : domain::density_per_radius, n, 1);
    if (!points_.empty() && !(r > points_.back().first)) fail(source_, line_no, "radii must strictly increase");
    if (c_.kind == Kind::dndlnr) n /= r;
    points_.emplace_back(r, n);
  }

  const std::string& source_;
  Columns c_;
  std::vector<TabulatedSegment> segments_;
  std::vector<std::pair<double, double>> points_;  // (r, n) in SI
};

}  // namespace

SizeDistribution read_distribution_csv(std::istream& in, const std::string& source) {
  std::optional<Rows> rows;  // once the header is read
  std::string raw;
  int line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    if (raw.size() > kMaxDistributionLineChars)
      fail(source, line_no, "line of " + std::to_string(raw.size()) + " characters; a row holds at most " +
                                std::to_string(kMaxDistributionLineChars));
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the header.
    if (line_no == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);
    std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    auto cells = split_csv(line);
    if (rows) {
      rows->add(line_no, cells);
      continue;
    }
    const std::optional<Columns> columns = read_header(cells);
    if (!columns)
      fail(source, line_no, "header " + quote_text(line, 80) + " does not state the columns and units; expected\n" +
                                distribution_file_format());
    rows.emplace(source, *columns);
  }
  if (!rows)
    throw std::invalid_argument(source + ": empty file; expected\n" + std::string(distribution_file_format()));
  return rows->finish();
}

}  // namespace attenuvis::weather
