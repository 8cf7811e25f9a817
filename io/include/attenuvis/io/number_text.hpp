// Numbers to and from text, the same way in every module.
#pragma once

#include <complex>
#include <string>
#include <string_view>

namespace attenuvis::io {

// Parses the whole of `text` as a finite double.  Throws std::invalid_argument
// "WHAT: 'TEXT' is not a number" (or "... is not finite", "... is out of the
// range of a double") so the caller's message names the input.
double parse_double(std::string_view text, std::string_view what);

// The shortest decimal text that reads back to the same double (1.7, 1550,
// 0.1): what an input echo or a machine-readable file should carry.
std::string shortest(double value);

// `digits` significant digits, as printf's %g would choose between fixed and
// exponent form (for values that carry an error bar, and for messages).
std::string significant(double value, int digits);

// Half a unit in the last printed digit of a decimal literal ("7.417859E-06"
// -> 5e-13, "0.10149104" -> 5e-9, "55.8066" -> 5e-5): how far a published
// value may lie from the exact one it rounds.
double half_unit_in_last_digit(std::string_view literal);

// The two number texts of a complex refractive index m = n + ik, written the
// one way every input of the project accepts: "n+ki" (also "n-ki", 'j' for
// 'i'), "n,k" (a comma or blanks between), or a bare "n" (imag = "0").  Only
// the shape is read here; each caller parses and range-checks the numbers so
// its messages name its own limits.  Throws std::invalid_argument "WHAT 'TEXT'
// should look like 1.33+1e-8i, 1.33,1e-8 or 1.33" for any other shape.
struct IndexText {
  std::string real, imag;
};
IndexText split_index_text(std::string_view text, std::string_view what);

// A complex refractive index as "n+ki" ("1.33+1e-08i"; "1.5" when k = 0), with
// the 6 significant digits of a stream's default format.
std::string index_text(std::complex<double> m);

}  // namespace attenuvis::io
