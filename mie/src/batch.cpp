// Batch evaluation and the text grammar of `attenuvis mie` (see batch.hpp).
//
// The text side is kept cheap so that the command's time is the physics':
// fields are views into the read buffer (no string per field or line),
// numbers go through std::from_chars and std::to_chars, and a row is
// formatted in a stack buffer and appended once.
#include "attenuvis/mie/batch.hpp"

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/spheres.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string_view>

namespace attenuvis::mie::batch {
namespace {

// Whole-token strict number parsing by strtod: "1.5x" or "" are errors, not
// 1.5 or 0.  The grammar's reference: parse_number below agrees with it on
// every token.
double parse_number_strtod(const std::string& token, const char* what) {
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

// True when the digits before the exponent of a decimal token are all zero,
// i.e. when the token names zero exactly rather than underflowing to it.
bool names_zero(std::string_view token) {
  for (const char c : token) {
    if (c == 'e' || c == 'E') break;
    if (c >= '1' && c <= '9') return false;
  }
  return true;
}

// std::from_chars where it gives strtod's answer, strtod otherwise.  Both
// round correctly (to nearest), so a whole decimal token that from_chars
// reads to a normal double, or to an exactly named zero, has the value strtod
// gives it; everything else (a leading '+', hexadecimal, inf and nan,
// subnormal or out-of-range values, a partial token) goes to strtod, with its
// values and messages.
double parse_number(std::string_view token, const char* what) {
  const char* end = token.data() + token.size();
  double v = 0;
  const auto r = std::from_chars(token.data(), end, v);
  if (r.ec == std::errc() && r.ptr == end && (std::isnormal(v) || (v == 0 && names_zero(token)))) return v;
  return parse_number_strtod(std::string(token), what);
}

// The most layers one line may list (the domain of attenuvis/mie/layered.hpp).
constexpr std::size_t kMaxLayerValues = 1000;

// The field separators: commas and the blanks of the C locale (a tab, the
// carriage return of a DOS line end).
bool is_separator(char c) {
  return c == ' ' || c == ',' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// Calls f(field) for each field of `text`, in order.
template <class F>
void for_each_field(std::string_view text, F&& f) {
  std::size_t i = 0;
  const std::size_t n = text.size();
  for (;;) {
    while (i < n && is_separator(text[i])) ++i;
    if (i == n) return;
    const std::size_t start = i;
    while (i < n && !is_separator(text[i])) ++i;
    f(text.substr(start, i - start));
  }
}

std::vector<std::string> split_fields(std::string_view text) {
  std::vector<std::string> fields;
  for_each_field(text, [&](std::string_view f) { fields.emplace_back(f); });
  return fields;
}

// The first fields of a line (as many as the longest header has) and how
// many there are in all.
struct LineFields {
  static constexpr std::size_t kKept = 10;
  std::array<std::string_view, kKept> field;
  std::size_t count = 0;
};

LineFields line_fields(std::string_view text) {
  LineFields f;
  for_each_field(text, [&](std::string_view s) {
    if (f.count < LineFields::kKept) f.field[f.count] = s;
    ++f.count;
  });
  return f;
}

// The output's own header (all of it, or its first three names "x m_re
// m_im"), so that a CSV written by `attenuvis mie` can be fed back.
bool is_header(const LineFields& f) {
  // Today's header, and the one written before qpr and terms were added.
  static constexpr std::array<std::string_view, 10> names = {"x",    "m_re",  "m_im", "qext", "qsca",
                                                             "qabs", "qback", "qpr",  "g",    "terms"};
  static constexpr std::array<std::string_view, 8> older = {"x", "m_re", "m_im", "qext", "qsca", "qabs", "qback", "g"};
  const auto matches = [&](const auto& h) {
    if (f.count != 3 && f.count != h.size()) return false;
    return std::equal(f.field.begin(), f.field.begin() + static_cast<std::ptrdiff_t>(f.count), h.begin());
  };
  return f.count > 0 && f.count <= LineFields::kKept && (matches(names) || matches(older));
}

// A batch mostly keeps one index over many lines (a size distribution, a
// table at one wavelength): the index is read, and written, once for each run
// of lines that repeat it.  A hit replays exactly what the miss computed: the
// same index fields read to the same values, the same values (bit for bit,
// -0 apart from 0) are written as the same text.
struct IndexMemo {
  bool read = false;
  std::string re_field, im_field;  // the index fields last read ...
  double re = 0, im = 0;           // ... and their values
  bool written = false;
  std::uint64_t re_bits = 0, im_bits = 0;  // the index last written ...
  char text[2 * 25] = {};                   // ... as ",re,im"
  std::size_t text_size = 0;
};

std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// The ';'-separated values of one field of a layered line.
std::vector<double> layer_values(std::string_view field, const char* what) {
  std::vector<double> v;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = std::min(field.find(';', start), field.size());
    if (v.size() == kMaxLayerValues)
      throw std::invalid_argument(std::string(what) + " lists more than " + std::to_string(kMaxLayerValues) +
                                  " layers");
    v.push_back(parse_number(field.substr(start, end - start), what));
    if (end == field.size()) return v;
    start = end + 1;
  }
}

// A layered line: the three fields as lists of the same length, checked
// layer by layer as a homogeneous line is (the core checks the domain).
Problem parse_layered(const LineFields& f) {
  const std::vector<double> x = layer_values(f.field[0], "x"), re = layer_values(f.field[1], "m_re"),
                            im = layer_values(f.field[2], "m_im");
  if (re.size() != x.size() || im.size() != x.size())
    throw std::invalid_argument("a layered line needs as many m_re and m_im as x values, got " +
                                std::to_string(x.size()) + ", " + std::to_string(re.size()) + " and " +
                                std::to_string(im.size()));
  Problem p;
  for (std::size_t l = 0; l < x.size(); ++l) {
    const std::string layer = "layer " + std::to_string(l) + ": ";
    if (!(x[l] > 0)) throw std::invalid_argument(layer + "x must be > 0");
    if (im[l] < 0) throw std::invalid_argument(layer + "m_im must be >= 0 (k > 0 absorbs)");
    if (re[l] < 0) throw std::invalid_argument(layer + "m_re must be >= 0");
    p.layer_x.push_back(x[l]);
    p.layer_m.emplace_back(re[l], im[l]);
  }
  p.x = p.layer_x.back();
  p.m = p.layer_m.back();
  return p;
}

std::optional<Problem> parse_fields(std::string_view line, IndexMemo* memo) {
  const LineFields f = line_fields(line.substr(0, line.find('#')));
  if (f.count == 0) return std::nullopt;
  if (is_header(f)) return std::nullopt;
  if (f.count != 3)
    throw std::invalid_argument("expected 3 fields 'x m_re m_im', got " + std::to_string(f.count));
  for (int i = 0; i < 3; ++i)
    if (f.field[i].find(';') != std::string_view::npos) return parse_layered(f);
  Problem p;
  p.x = parse_number(f.field[0], "x");
  double n = 0, k = 0;
  if (memo && memo->read && f.field[1] == memo->re_field && f.field[2] == memo->im_field) {
    n = memo->re, k = memo->im;
  } else {
    n = parse_number(f.field[1], "m_re");
    k = parse_number(f.field[2], "m_im");
    if (memo) {
      memo->re_field.assign(f.field[1]), memo->im_field.assign(f.field[2]);
      memo->re = n, memo->im = k, memo->read = true;
    }
  }
  if (p.x <= 0) throw std::invalid_argument("x must be > 0, got " + std::string(f.field[0]));
  if (k < 0) throw std::invalid_argument("m_im must be >= 0 (k > 0 absorbs), got " + std::string(f.field[2]));
  if (n < 0) throw std::invalid_argument("m_re must be >= 0, got " + std::string(f.field[1]));
  p.m = {n, k};
  return p;
}

// One CSV row without its line end.  The input as the shortest text that
// reads back to it (1.33, not 1.3300000000000001); the results at 17
// significant digits, %.17g by std::to_chars (printf's text without its
// locale and format-string machinery), which read back exactly.
void append_results(std::string& out, const Efficiencies<double>& q) {
  char buf[6 * 25 + 21 + 7];
  char* at = buf;
  char* const end = buf + sizeof buf;
  for (const double v : {q.qext, q.qsca, q.qabs, q.qback, q.qpr, q.g}) {
    *at++ = ',';
    at = std::to_chars(at, end, v, std::chars_format::general, 17).ptr;
  }
  *at++ = ',';
  at = std::to_chars(at, end, q.terms).ptr;
  out.append(buf, at);
}

// A layered row: the three input lists as read (each value's shortest text),
// then the results.
void append_layered_row(std::string& out, const Problem& p, const Efficiencies<double>& q) {
  const auto list = [&](auto value_of) {
    for (std::size_t l = 0; l < p.layer_x.size(); ++l) {
      char buf[25];
      if (l > 0) out += ';';
      out.append(buf, std::to_chars(buf, buf + sizeof buf, value_of(l)).ptr);
    }
  };
  list([&](std::size_t l) { return p.layer_x[l]; });
  out += ',';
  list([&](std::size_t l) { return p.layer_m[l].real(); });
  out += ',';
  list([&](std::size_t l) { return p.layer_m[l].imag(); });
  append_results(out, q);
}

void append_row(std::string& out, const Problem& p, const Efficiencies<double>& q, IndexMemo* memo) {
  if (!p.layer_x.empty()) return append_layered_row(out, p, q);
  // 9 numbers of at most 24 characters ("-2.2250738585072014e-308"), 20
  // digits of the term count, 9 commas.
  char buf[9 * 24 + 20 + 9];
  char* at = buf;
  char* const end = buf + sizeof buf;
  at = std::to_chars(at, end, p.x).ptr;
  const std::uint64_t re_bits = bits_of(p.m.real()), im_bits = bits_of(p.m.imag());
  if (memo && memo->written && memo->re_bits == re_bits && memo->im_bits == im_bits) {
    at = std::copy_n(memo->text, memo->text_size, at);
  } else {
    char* const index_text = at;
    for (const double v : {p.m.real(), p.m.imag()}) {
      *at++ = ',';
      at = std::to_chars(at, end, v).ptr;
    }
    if (memo) {
      memo->text_size = static_cast<std::size_t>(at - index_text);
      std::copy(index_text, at, memo->text);
      memo->re_bits = re_bits, memo->im_bits = im_bits, memo->written = true;
    }
  }
  for (const double v : {q.qext, q.qsca, q.qabs, q.qback, q.qpr, q.g}) {
    *at++ = ',';
    at = std::to_chars(at, end, v, std::chars_format::general, 17).ptr;
  }
  *at++ = ',';
  at = std::to_chars(at, end, q.terms).ptr;
  out.append(buf, at);
}

// Good lines are collected in chunks and evaluated together by spheres()
// (several spheres per vector instruction, threads over cores), the layered
// ones by layered_spheres(); rows are written in input order.  Messages for
// lines the core rejects (outside the domain of attenuvis/mie.hpp or
// attenuvis/mie/layered.hpp) are written when their chunk is evaluated.
class ChunkedRows {
 public:
  ChunkedRows(std::ostream& out, std::ostream& err, const Options& options) : out_(out), err_(err) {
    spheres_options_.options = options;
  }
  void add(Problem&& p, std::size_t line_number) {
    if (p.layer_x.empty()) {
      order_.push_back({false, xs_.size()});
      xs_.push_back(p.x);
      ms_.push_back(p.m);
    } else {
      order_.push_back({true, layered_.size()});
      if (layered_offsets_.empty()) layered_offsets_.push_back(0);
      layered_x_.insert(layered_x_.end(), p.layer_x.begin(), p.layer_x.end());
      layered_m_.insert(layered_m_.end(), p.layer_m.begin(), p.layer_m.end());
      layered_offsets_.push_back(layered_x_.size());
      layered_.push_back(std::move(p));
    }
    line_of_.push_back(line_number);
    if (order_.size() == kChunk) evaluate();
  }
  // Evaluates the lines collected so far and writes their rows (or messages).
  void evaluate() {
    q_.resize(xs_.size());
    layered_q_.resize(layered_.size());
    std::vector<SphereError> errors = spheres(xs_.data(), ms_.data(), xs_.size(), q_.data(), spheres_options_);
    std::vector<SphereError> layered_errors;
    if (!layered_.empty())
      layered_errors = layered_spheres(layered_offsets_.data(), layered_x_.data(), layered_m_.data(),
                                       layered_.size(), layered_q_.data(), spheres_options_);
    std::size_t e = 0, le = 0;
    for (std::size_t k = 0; k < order_.size(); ++k) {
      const auto [layered, i] = order_[k];
      std::vector<SphereError>& errs = layered ? layered_errors : errors;
      std::size_t& next = layered ? le : e;
      if (next < errs.size() && errs[next].index == i) {
        ++bad_;
        err_ << "line " << line_of_[k] << ": " << errs[next++].message << '\n';
        continue;
      }
      if (layered) append_row(text_, layered_[i], layered_q_[i], nullptr);
      else append_row(text_, Problem{xs_[i], ms_[i], {}, {}}, q_[i], &index_memo_);
      text_ += '\n';
    }
    out_ << text_;
    text_.clear();
    xs_.clear();
    ms_.clear();
    layered_.clear();
    layered_x_.clear();
    layered_m_.clear();
    layered_offsets_.clear();
    order_.clear();
    line_of_.clear();
  }
  std::size_t bad() const { return bad_; }
  // The reader's memo of the index (parse_fields), shared with the writer's.
  IndexMemo& index_memo() { return index_memo_; }

 private:
  static constexpr std::size_t kChunk = 4096;
  std::ostream& out_;
  std::ostream& err_;
  SpheresOptions spheres_options_;
  IndexMemo index_memo_;
  std::vector<std::pair<bool, std::size_t>> order_;  // (layered, index in its list), by line
  std::vector<std::size_t> line_of_;
  std::vector<double> xs_;
  std::vector<std::complex<double>> ms_;
  std::vector<Efficiencies<double>> q_;
  std::vector<Problem> layered_;
  std::vector<std::size_t> layered_offsets_;
  std::vector<double> layered_x_;
  std::vector<std::complex<double>> layered_m_;
  std::vector<Efficiencies<double>> layered_q_;
  std::string text_;
  std::size_t bad_ = 0;
};

// Lines cut out of 64 KiB blocks read straight into `pending_` (std::getline
// on a stream synchronised with C stdio, std::cin by default, reads one
// character per library call); each line is a view into the block, parsed
// where it lies and valid until the next call.
class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(in) {}
  bool next(std::string_view& line) {
    for (;;) {
      const auto nl = pending_.find('\n', scan_);
      if (nl != std::string::npos) {
        line = std::string_view(pending_).substr(pos_, nl - pos_);
        pos_ = scan_ = nl + 1;
        return true;
      }
      scan_ = pending_.size();
      if (!more_) {
        if (pos_ >= pending_.size()) return false;
        line = std::string_view(pending_).substr(pos_);  // last line without a newline
        pos_ = pending_.size();
        return true;
      }
      read_block();
    }
  }

 private:
  static constexpr std::size_t kBlock = std::size_t(1) << 16;
  // Drops the lines already handed out and appends the next block.
  void read_block() {
    pending_.erase(0, pos_);
    scan_ -= pos_;
    pos_ = 0;
    const std::size_t kept = pending_.size();
    pending_.resize(kept + kBlock);
    in_.read(pending_.data() + kept, static_cast<std::streamsize>(kBlock));
    const std::streamsize got = in_.gcount();
    pending_.resize(kept + static_cast<std::size_t>(std::max<std::streamsize>(got, 0)));
    if (!in_) more_ = false;  // end of input (or a read error): what was read is kept
  }
  std::istream& in_;
  std::string pending_;
  std::size_t pos_ = 0;   // start of the unread part of `pending_`
  std::size_t scan_ = 0;  // where the search for its line end resumes (a long line is searched once)
  bool more_ = true;
};

}  // namespace

std::optional<Problem> parse_line(const std::string& line) { return parse_fields(line, nullptr); }

const char* csv_header() { return "x,m_re,m_im,qext,qsca,qabs,qback,qpr,g,terms"; }

std::string csv_row(const Problem& p, const Efficiencies<double>& q) {
  std::string row;
  append_row(row, p, q, nullptr);
  return row;
}

// Messages for lines that fail to parse are written as they are read.
std::size_t run(std::istream& in, std::ostream& out, std::ostream& err, const Options& options) {
  out << csv_header() << '\n';
  ChunkedRows rows(out, err, options);
  LineReader reader(in);
  std::size_t unparsed = 0, line_number = 0;
  for (std::string_view line; reader.next(line);) {
    ++line_number;
    try {
      std::optional<Problem> p = parse_fields(line, &rows.index_memo());
      if (p) rows.add(std::move(*p), line_number);
    } catch (const std::exception& e) {
      ++unparsed;
      err << "line " << line_number << ": " << e.what() << '\n';
    }
  }
  rows.evaluate();
  return unparsed + rows.bad();
}

std::complex<double> parse_refractive_index(const std::string& text) {
  const io::IndexText parts = io::split_index_text(text, "refractive index");
  const double n = parse_number(parts.real, "n");
  const double k = parse_number(parts.imag, "k");
  if (n < 0 || k < 0) throw std::invalid_argument("refractive index needs n >= 0 and k >= 0, got '" + text + "'");
  return {n, k};
}

std::vector<LayerText> parse_layers(const std::string& text, const char* option) {
  std::vector<LayerText> layers;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    const std::string where = std::string(option) + " layer " + std::to_string(layers.size()) + " '" + item + "': ";
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == item.size())
      throw std::invalid_argument(where + "expected size:index, e.g. 0.5:1.75+0.44i");
    if (layers.size() == kMaxLayerValues)
      throw std::invalid_argument(std::string(option) + " lists more than " + std::to_string(kMaxLayerValues) +
                                  " layers");
    LayerText layer;
    layer.size = item.substr(0, colon);
    const std::string index = item.substr(colon + 1);
    if (index == "pec") {
      if (!layers.empty())
        throw std::invalid_argument(where + "only the core (the first layer) may be a perfect conductor");
    } else {
      if (index.find(',') != std::string::npos)
        throw std::invalid_argument(where + "write the index as n+ki");
      try {
        layer.m = parse_refractive_index(index);
      } catch (const std::exception& e) {
        throw std::invalid_argument(where + e.what());
      }
    }
    layers.push_back(std::move(layer));
    if (end == text.size()) return layers;
    start = end + 1;
  }
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
