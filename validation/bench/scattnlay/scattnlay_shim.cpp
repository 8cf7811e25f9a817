// One C entry point around scattnlay's nmie::nMie (double precision), for
// the benchmark mie_layered_speed: compiled with the user's scattnlay
// sources by build_scattnlay.sh, never with attenuvis.
#include <complex>
#include <vector>

#include "nmie.hpp"

// Layers core first: x[l], m[l] = m_re_im[2l] + i m_re_im[2l+1]; writes
// Qext, Qsca, Qabs, Qbk, Qpr, g to q; returns the number of terms (or -1 on
// an exception).
extern "C" int attenuvis_scattnlay_efficiencies(unsigned layers, const double* x, const double* m_re_im,
                                                double* q) {
  try {
    std::vector<double> xs(x, x + layers);
    std::vector<std::complex<double>> ms;
    for (unsigned l = 0; l < layers; ++l) ms.emplace_back(m_re_im[2 * l], m_re_im[2 * l + 1]);
    std::vector<double> theta;
    std::vector<std::complex<double>> s1, s2;
    double albedo = 0;
    return nmie::nMie(layers, xs, ms, 0, theta, &q[0], &q[1], &q[2], &q[3], &q[4], &q[5], &albedo, s1, s2);
  } catch (...) {
    return -1;
  }
}
