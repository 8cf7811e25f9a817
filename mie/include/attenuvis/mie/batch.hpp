// Batch evaluation and the small text grammar of the `attenuvis mie` command.
//
// Batch input: one problem per line, "x m_re m_im" separated by whitespace
// and/or commas; '#' starts a comment; blank lines and the output's own
// header line (x,m_re,m_im[,qext,...]) are skipped.  A layered sphere
// (attenuvis/mie/layered.hpp) lists its layers from the core out in each of
// the three fields, separated by ';': "5.71;11.42 1.75;1.43 0.44;1e-8" is a
// soot core (x 5.71) in a sulphate shell (outer x 11.42); its row echoes the
// three lists.  Output: CSV
// with the header x,m_re,m_im,qext,qsca,qabs,qback,qpr,g,terms (the columns of
// the single-sphere output); the input x, m_re, m_im
// as the shortest text that reads back to the same double, the results with
// 17 significant digits (round-trip for double).  A bad line (parse error, x <= 0, k < 0,
// non-finite value, wrong number of fields) is reported with its line number
// and skipped; every good line is still computed.
#pragma once

#include <complex>
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie::batch {

// One sphere of the batch input: size parameter and relative index.
struct Problem {
  double x = 0;  // the sphere's (a layered one's outer) size parameter
  std::complex<double> m;
  // A layered sphere: every layer's size parameter and index, core first
  // (x and m above are the outer layer's); empty for a homogeneous sphere.
  std::vector<double> layer_x;
  std::vector<std::complex<double>> layer_m;
};

// One input line: nullopt for a blank, comment-only or header line; throws
// std::invalid_argument (message without the line number) for a bad one.
std::optional<Problem> parse_line(const std::string& line);

// The output's header line and one sphere's row: its input as the shortest text
// that reads back to it, the efficiencies with 17 significant digits.
const char* csv_header();  // "x,m_re,m_im,qext,qsca,qabs,qback,qpr,g,terms"
std::string csv_row(const Problem& p, const Efficiencies<double>& q);

// Reads `in` to the end, writes the header and one row per good line to
// `out`, one "line N: <why>" message per bad line to `err`.  Returns the
// number of bad lines.  The spheres are evaluated in chunks by spheres()
// (attenuvis/mie/spheres.hpp), with the same results as sphere(), the layered
// ones by layered_spheres().
std::size_t run(std::istream& in, std::ostream& out, std::ostream& err, const Options& options = {});

// "1.33+1e-8i", "1.33,1e-8" or "1.33" (k = 0) -> m, the project's one index
// syntax (attenuvis/io/number_text.hpp: split_index_text); throws
// std::invalid_argument.
std::complex<double> parse_refractive_index(const std::string& text);
// One layer of the `--layers` text: a size (a radius with or without unit,
// or a size parameter: the caller says which) and its index, or none for a
// perfectly conducting core ("pec").
struct LayerText {
  std::string size;
  std::optional<std::complex<double>> m;  // nullopt: perfect conductor
};
// "0.5:1.75+0.44i,1.0:1.43+1e-8i" -> the layers from the core out (indices
// as 'n+ki' or 'n'; 'pec' for a perfectly conducting core, first layer only);
// throws std::invalid_argument naming the layer.
std::vector<LayerText> parse_layers(const std::string& text, const char* option);

// "0:180:1" (start:stop:step, stop included when hit within 1e-9·step; the
// grid's angles rounded to 12 significant digits, so 0:1:0.1 gives 0.3),
// "30" or "0,45,90" -> angles in degrees; throws std::invalid_argument.
std::vector<double> parse_angles(const std::string& text);

}  // namespace attenuvis::mie::batch
