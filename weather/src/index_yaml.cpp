// refractiveindex.info YAML files (index_file.hpp): the subset of YAML the
// database writes, read line by line.  A file is top-level keys at column 0;
// REFERENCES and COMMENTS are kept as the citation, DATA is a list of items
// (`- type: ...` with further `key: value` lines at the item's key column and
// `key: |` block scalars whose lines are indented deeper), and every other
// key (SPECS, CONDITIONS, ...) is skipped with its indented block.  No YAML
// library is among the project's dependencies; this reader accepts the
// database's layout and names the file and line of anything else.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/weather/index_file.hpp"
#include "index_text.hpp"

namespace attenuvis::weather {
namespace {

struct Line {
  int no = 0;       // 1-based line number in the file
  int indent = 0;   // leading blanks
  std::string text; // without the indentation and trailing blanks
};

// The lines that carry content: blank lines and '#' comments dropped, tabs
// in the indentation refused (YAML forbids them, and they would misplace a line).
std::vector<Line> content_lines(const std::string& text, const std::string& source) {
  std::vector<Line> out;
  std::size_t start = 0;
  int no = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string raw = text.substr(start, end - start);
    start = end + 1;
    ++no;
    std::size_t indent = 0;
    while (indent < raw.size() && (raw[indent] == ' ' || raw[indent] == '\t')) {
      if (raw[indent] == '\t')
        throw std::runtime_error(source + ":" + std::to_string(no) + ": a tab in the indentation (YAML indents with blanks)");
      ++indent;
    }
    const std::string t = detail::trimmed(raw);
    if (t.empty() || t[0] == '#') continue;
    out.push_back({no, static_cast<int>(indent), t});
    if (end == text.size()) break;
  }
  return out;
}

// "key: value" -> {key, value}; nullopt where the text has no ':' after a key.
std::optional<std::pair<std::string, std::string>> key_value(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0) return std::nullopt;
  if (colon + 1 < text.size() && text[colon + 1] != ' ') return std::nullopt;
  return std::make_pair(detail::trimmed(text.substr(0, colon)), detail::trimmed(text.substr(colon + 1)));
}

std::string unquoted(std::string v) {
  if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front()) v = v.substr(1, v.size() - 2);
  return v;
}

// A value: inline text and the lines below it, each with its line number.
struct Value {
  std::vector<Line> lines;
  int line = 0;  // where the key stands
  std::string joined() const {
    std::string out;
    for (const auto& l : lines) out += (out.empty() ? "" : " ") + l.text;
    return out;
  }
};

class Reader {
 public:
  Reader(std::vector<Line> lines, std::string source) : lines_(std::move(lines)), source_(std::move(source)) {}

  // The value of the key on line i (key column `indent`): inline, or the
  // block below it; the cursor moves past it.
  Value value_of(const std::string& inline_text, int indent) {
    Value v;
    v.line = lines_[i_].no;
    ++i_;
    const std::string t = unquoted(inline_text);
    const bool block = !t.empty() && (t[0] == '|' || t[0] == '>');
    if (!t.empty() && !block) v.lines.push_back({v.line, indent, t});
    // Deeper lines continue the value: a block scalar's lines, or a plain
    // scalar folded over several lines (YAML 1.2, sec. 7.3.3).
    while (i_ < lines_.size() && lines_[i_].indent > indent) v.lines.push_back(lines_[i_++]);
    return v;
  }

  [[noreturn]] void fail(int line, const std::string& why) const {
    throw std::runtime_error(source_ + ":" + std::to_string(line) + ": " + why);
  }

  bool done() const { return i_ >= lines_.size(); }
  const Line& line() const { return lines_[i_]; }
  void skip() { ++i_; }
  const std::string& source() const { return source_; }

 private:
  std::vector<Line> lines_;
  std::string source_;
  std::size_t i_ = 0;
};

// One DATA item, its keys by name.
struct Item {
  int line = 0;
  std::map<std::string, Value> keys;
};

// The items of DATA: `- key: value` lines at one indentation, each followed
// by its further keys at the column of the first one.
std::vector<Item> read_items(Reader& r, int data_line) {
  std::vector<Item> items;
  if (r.done() || r.line().text[0] != '-') r.fail(data_line, "DATA must be a list of items (`- type: ...`)");
  const int dash = r.line().indent;
  while (!r.done() && r.line().indent == dash && r.line().text[0] == '-') {
    Item item;
    item.line = r.line().no;
    std::string first = detail::trimmed(r.line().text.substr(1));
    int key_column = dash + 1 + static_cast<int>(r.line().text.size() - 1 - first.size());
    bool first_line = true;
    while (!r.done()) {
      if (!first_line && (r.line().indent != key_column)) break;
      const std::string text = first_line ? first : r.line().text;
      const auto kv = key_value(text);
      if (!kv) r.fail(r.line().no, "expected `key: value` in a DATA item, found '" + text.substr(0, 40) + "'");
      if (item.keys.count(kv->first)) r.fail(r.line().no, "the item gives " + kv->first + " twice");
      item.keys[kv->first] = r.value_of(kv->second, key_column);
      first_line = false;
    }
    items.push_back(std::move(item));
  }
  if (!r.done() && r.line().indent > 0) r.fail(r.line().no, "a line that belongs to no DATA item (check its indentation)");
  return items;
}

// What one item gives: n, k or both, as columns or a formula, and its range.
struct Piece {
  int line = 0;
  std::string what;  // "tabulated nk", "formula 2"
  std::optional<std::variant<MaterialIndex::Column, MaterialIndex::Formula>> n;
  std::optional<MaterialIndex::Column> k;
  double lo = 0, hi = 0;
};

// The rows of a `data: |` block: wavelength and `columns` - 1 values each.
void read_rows(const Reader& r, const Value& data, std::size_t columns, Piece& p) {
  MaterialIndex::Column n, k;
  const bool has_n = p.what != "tabulated k", has_k = p.what != "tabulated n";
  for (const Line& row : data.lines) {
    const std::string where = r.source() + ":" + std::to_string(row.no);
    const auto f = detail::fields(row.text);
    if (f.size() != columns)
      r.fail(row.no, std::to_string(f.size()) + " column(s); '" + p.what + "' rows have " + std::to_string(columns) +
                         " (wavelength in um, then " + (columns == 3 ? "n and k)" : has_n ? "n)" : "k)"));
    const double w = detail::number(f[0], where, "wavelength");
    if (!(w > 0)) r.fail(row.no, "wavelength " + f[0] + " um must be > 0");
    if (!n.wavelength_um.empty() && !(w > n.wavelength_um.back()))
      r.fail(row.no, "wavelength " + f[0] + " um does not increase on the row before");
    n.wavelength_um.push_back(w);
    if (has_n) {
      const double v = detail::number(f[1], where, "n");
      if (!(v > 0)) r.fail(row.no, "n = " + f[1] + " must be > 0");
      n.value.push_back(v);
    }
    if (has_k) {
      const double v = detail::number(f[columns - 1], where, "k");
      if (v < 0)
        r.fail(row.no, "k = " + f[columns - 1] + " is negative: refractiveindex.info gives k >= 0 (m = n + ik); a "
                       "file of the m = n - ik convention needs its signs turned (or three columns with `# sign: n-ik`)");
      k.value.push_back(v);
    }
  }
  if (n.wavelength_um.size() < 2) r.fail(data.line, "'" + p.what + "' needs at least two rows of data");
  k.wavelength_um = n.wavelength_um;
  if (has_n) p.n = n;
  if (has_k) p.k = k;
  p.lo = n.wavelength_um.front();
  p.hi = n.wavelength_um.back();
}

// Coefficient counts the formulas take: C1 then pairs (1, 2, 3, 5, 6), or at most their defined terms.
bool coefficient_count_fits(int type, std::size_t count) {
  if (count == 0) return false;
  switch (type) {
    case 4: return count <= 17;
    case 7: return count <= 6;
    case 8: return count <= 4;
    case 9: return count <= 6;
    default: return count % 2 == 1;
  }
}

void read_formula(const Reader& r, const Item& item, int type, Piece& p) {
  const auto coefficients = item.keys.find("coefficients");
  auto range = item.keys.find("wavelength_range");
  if (range == item.keys.end()) range = item.keys.find("range");  // the database's older spelling
  if (coefficients == item.keys.end()) r.fail(item.line, p.what + " needs `coefficients:`");
  if (range == item.keys.end()) r.fail(item.line, p.what + " needs `wavelength_range: MIN MAX` (um)");
  const std::string where_c = r.source() + ":" + std::to_string(coefficients->second.line);
  MaterialIndex::Formula f;
  f.type = type;
  for (const auto& c : detail::fields(coefficients->second.joined())) f.coefficients.push_back(detail::number(c, where_c, "coefficient"));
  if (!coefficient_count_fits(type, f.coefficients.size()))
    r.fail(coefficients->second.line, std::to_string(f.coefficients.size()) + " coefficients do not fit formula " +
                                          std::to_string(type) + " (index_file.hpp lists its terms)");
  const std::string where_r = r.source() + ":" + std::to_string(range->second.line);
  const auto bounds = detail::fields(range->second.joined());
  if (bounds.size() != 2) r.fail(range->second.line, "wavelength_range needs two numbers, MIN MAX in um");
  p.lo = detail::number(bounds[0], where_r, "wavelength range");
  p.hi = detail::number(bounds[1], where_r, "wavelength range");
  if (!(p.lo > 0 && p.hi > p.lo)) r.fail(range->second.line, "wavelength_range needs 0 < MIN < MAX (um)");
  p.n = f;
}

Piece read_piece(const Reader& r, const Item& item) {
  Piece p;
  p.line = item.line;
  const auto type = item.keys.find("type");
  if (type == item.keys.end()) r.fail(item.line, "a DATA item without `type:`");
  p.what = unquoted(type->second.joined());
  const auto data = item.keys.find("data");
  if (p.what == "tabulated nk" || p.what == "tabulated n" || p.what == "tabulated k") {
    if (data == item.keys.end()) r.fail(item.line, "'" + p.what + "' needs a `data: |` block");
    read_rows(r, data->second, p.what == "tabulated nk" ? 3 : 2, p);
  } else if (p.what.rfind("formula ", 0) == 0 && p.what.size() == 9 && p.what[8] >= '1' && p.what[8] <= '9') {
    read_formula(r, item, p.what[8] - '0', p);
  } else {
    r.fail(type->second.line, "type '" + p.what.substr(0, 40) +
                                  "' is not tabulated nk, tabulated n, tabulated k or formula 1..9");
  }
  return p;
}

// "<a href=...>Appl. Opt.</a> 12, 555" -> "Appl. Opt. 12, 555": the citation without markup.
std::string plain_text(const std::string& html) {
  std::string out;
  bool in_tag = false;
  for (char ch : html) {
    if (ch == '<') in_tag = true;
    else if (ch == '>') in_tag = false;
    else if (!in_tag && !(ch == ' ' && (out.empty() || out.back() == ' '))) out += ch;
  }
  return detail::trimmed(out).substr(0, 500);
}

MaterialIndex assemble(const Reader& r, const std::vector<Piece>& pieces, const std::string& citation) {
  const Piece* n = nullptr;
  const Piece* k = nullptr;
  double lo = 0, hi = INFINITY;
  std::string what;
  for (const Piece& p : pieces) {
    if (p.n && n) r.fail(p.line, "a second item gives n (the first at line " + std::to_string(n->line) + ")");
    if (p.k && k) r.fail(p.line, "a second item gives k (the first at line " + std::to_string(k->line) + ")");
    if (p.n) n = &p;
    if (p.k) k = &p;
    lo = std::max(lo, p.lo);
    hi = std::min(hi, p.hi);
    what += (what.empty() ? "" : " + ") + p.what;
  }
  if (!n) r.fail(pieces.empty() ? 1 : pieces.front().line, "no DATA item gives n");
  if (!(hi >= lo))
    r.fail(pieces.back().line, "the items' wavelength ranges do not overlap");
  std::vector<MaterialIndex::Column> k_column;
  if (k) k_column.push_back(*k->k);
  return MaterialIndex(r.source(), *n->n, k_column, lo, hi,
                       "refractiveindex.info YAML, " + what + ", " + io::significant(lo, 6) + " - " +
                           io::significant(hi, 6) + " um, m = n + ik",
                       citation);
}

}  // namespace

MaterialIndex parse_refractiveindex_yaml(const std::string& text, const std::string& source) {
  Reader r(content_lines(text, source), source);
  std::vector<Piece> pieces;
  std::string references, comments;
  bool data_seen = false;
  while (!r.done()) {
    const Line line = r.line();
    if (line.indent != 0) r.fail(line.no, "expected a top-level key (REFERENCES, COMMENTS, DATA, SPECS)");
    const auto kv = key_value(line.text);
    if (!kv) r.fail(line.no, "expected `KEY:` at the start of a line, found '" + line.text.substr(0, 40) + "'");
    if (kv->first == "DATA") {
      if (data_seen) r.fail(line.no, "a second DATA list");
      data_seen = true;
      if (!kv->second.empty()) r.fail(line.no, "DATA must be a list of items on the lines below it");
      r.skip();
      for (const Item& item : read_items(r, line.no)) pieces.push_back(read_piece(r, item));
    } else {
      const Value v = r.value_of(kv->second, 0);
      if (kv->first == "REFERENCES") references = plain_text(v.joined());
      if (kv->first == "COMMENTS") comments = plain_text(v.joined());
    }
  }
  if (!data_seen) throw std::runtime_error(source + ": no DATA list (a refractiveindex.info file has one)");
  return assemble(r, pieces, references.empty() ? comments : references);
}

}  // namespace attenuvis::weather
