// The complex refractive index of a material read from a file, as a function
// of wavelength: what `:index=FILE` gives any Mie condition, and how the OPAC
// components' indices are read.  Three formats:
//
//   refractiveindex.info YAML (a file ending in .yml or .yaml): the subset the
//     database uses (M. N. Polyanskiy, "Refractiveindex.info database of
//     optical constants", Sci. Data 11, 94 (2024)):
//     REFERENCES and COMMENTS (kept as the citation), a DATA list whose items
//     are `type: tabulated nk | tabulated n | tabulated k` with a `data: |`
//     block of rows (wavelength in um, then n and/or k), or `type: formula N`
//     (N = 1..9, the database's dispersion formulas, index_formula below) with
//     `coefficients:` and `wavelength_range:` (um).  One item gives n, at most
//     one more gives k (k = 0 without one); the range is the common one.  The
//     database's k is >= 0 (m = n + ik, as here); a negative k is refused.
//   three columns (any other file): wavelength (um), n, k per line, separated
//     by blanks or commas; '#' starts a comment line.  The sign of k is read
//     by the rule `ImaginarySign`: stated by the caller, stated in the file by
//     a comment line `# sign: n+ik` or `# sign: n-ik`, or else detected: all
//     k >= 0 is m = n + ik, all k <= 0 is m = n - ik (turned to k >= 0); a
//     file with both signs is refused at the first line that differs.
//   OPAC (data/opac/refractive_indices): three columns whose k is given
//     negative (m = n - ik, Hess et al. 1998): read with ImaginarySign::n_minus_ik.
//
// Tabulated values are interpolated in wavelength as the water tables are
// (refractive_index.hpp): n linear in ln(lambda), ln k linear in ln(lambda)
// where both neighbours have k > 0, else k linear in ln(lambda).  A
// wavelength outside the file's range is an error naming the wavelength, the
// file and its range; nothing is extrapolated.  Every reading error names
// the file and the line.
#pragma once

#include <complex>
#include <string>
#include <variant>
#include <vector>

namespace attenuvis::weather {

// How the sign of k in a three-column file is read.
enum class ImaginarySign {
  detect,      // from the file's `# sign:` line, else from the signs of its k column
  n_plus_ik,   // k >= 0 in the file (Bohren & Huffman; refractiveindex.info)
  n_minus_ik,  // k <= 0 in the file (OPAC, Wiscombe's MIEV0)
};

// A material's refractive index m(lambda) = n + ik read from a file, over
// the wavelengths the file covers.
class MaterialIndex {
 public:
  // m = n + ik (k >= 0) at a vacuum wavelength in metres.  Throws
  // std::invalid_argument outside [min_wavelength_m, max_wavelength_m],
  // naming the wavelength, the file and its range, and where a formula has
  // no real index there (n^2 <= 0).
  std::complex<double> at(double wavelength_m) const;
  double min_wavelength_m() const { return lo_um_ * 1e-6; }
  double max_wavelength_m() const { return hi_um_ * 1e-6; }
  const std::string& source() const { return source_; }        // the path it was read from
  const std::string& description() const { return description_; }  // format, pieces, range, sign rule
  const std::string& citation() const { return citation_; }    // REFERENCES, or the comment lines; may be empty

  // Rows of wavelength (um, increasing) and one column (n or k).
  struct Column {
    std::vector<double> wavelength_um, value;
  };
  // A refractiveindex.info dispersion formula for n, wavelength in um.
  struct Formula {
    int type = 0;
    std::vector<double> coefficients;
  };
  // The pieces: n from a column or a formula, k from a column or zero.
  MaterialIndex(std::string source, std::variant<Column, Formula> n, std::vector<Column> k, double lo_um,
                double hi_um, std::string description, std::string citation);

 private:
  std::string source_, description_, citation_;
  std::variant<Column, Formula> n_;
  std::vector<Column> k_;  // empty or one column
  double lo_um_ = 0, hi_um_ = 0;
};

// By extension: .yml or .yaml as refractiveindex.info YAML, anything else as
// three columns with the sign detected.  Throws std::runtime_error
// "PATH:LINE: what" for a file that cannot be read as its format.
MaterialIndex read_index_file(const std::string& path);

// The readers on text already in memory; `source` names it in messages.
MaterialIndex parse_refractiveindex_yaml(const std::string& text, const std::string& source);
MaterialIndex parse_index_columns(const std::string& text, const std::string& source, ImaginarySign sign);

// n of refractiveindex.info's formula `type` (1..9) with coefficients c
// (c[0] is the database's C1), wavelength in um:
//   1 Sellmeier     n^2 - 1 = C1 + sum C(2i) l^2 / (l^2 - C(2i+1)^2)
//   2 Sellmeier-2   n^2 - 1 = C1 + sum C(2i) l^2 / (l^2 - C(2i+1))
//   3 polynomial    n^2 = C1 + sum C(2i) l^C(2i+1)
//   4 RI.INFO       n^2 = C1 + C2 l^C3 / (l^2 - C4^C5) + C6 l^C7 / (l^2 - C8^C9) + sum_{i>=5} C(2i) l^C(2i+1)
//   5 Cauchy        n = C1 + sum C(2i) l^C(2i+1)
//   6 gases         n - 1 = C1 + sum C(2i) / (C(2i+1) - l^-2)
//   7 Herzberger    n = C1 + C2 / (l^2 - 0.028) + C3 / (l^2 - 0.028)^2 + C4 l^2 + C5 l^4 + C6 l^6
//   8 retro         (n^2 - 1) / (n^2 + 2) = C1 + C2 l^2 / (l^2 - C3) + C4 l^2
//   9 exotic        n^2 = C1 + C2 / (l^2 - C3) + C4 (l - C5) / ((l - C5)^2 + C6)
// Returns n^2 for the forms that give n^2 (so that the caller can refuse
// n^2 <= 0) and n for 5, 6 and 7; formula_gives_square says which.
double index_formula(int type, const std::vector<double>& c, double wavelength_um);
bool formula_gives_square(int type);

}  // namespace attenuvis::weather
