// Text and JSON output of `attenuvis mie` for one sphere: efficiencies, the
// per-sphere lidar quantities, and on request the amplitudes, the scattering
// matrix with the phase function, and the Legendre / generalised-spherical-
// function moments.  Formatting only; every number comes from attenuvis::mie.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"

namespace attenuvis::cli {

// What the user asked for, as they wrote it where it is echoed.
struct MieEcho {
  double x = 0;                    // a layered sphere: its outer x
  std::complex<double> m;          // relative index used (particle / medium); layered: the outer layer's
  std::vector<double> layer_x;     // a layered sphere, core first (empty: homogeneous)
  std::vector<std::complex<double>> layer_m;  // one per layer, or per shell on a conducting core
  bool conducting_core = false;
  std::string size_text;           // "" for --x, else how x was formed from radii and the wavelength
  std::string term_rule;           // "converged" | "wiscombe"
};

struct MieResult {
  mie::Scattering<double> s;                           // efficiencies, S1/S2 if --angles
  std::optional<mie::ScatteringMatrix> matrix;         // --phase
  std::optional<std::vector<double>> moments;          // --moments
  std::optional<mie::ScatteringMatrixExpansion<double>> expansion;  // --moments --polarised
};

void print_mie_text(const MieEcho& echo, const MieResult& r);
void print_mie_json(const MieEcho& echo, const MieResult& r);

}  // namespace attenuvis::cli
