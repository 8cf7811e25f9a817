// Time per call of layered spheres (attenuvis/mie/layered.hpp) beside the
// homogeneous sphere() at the same outer x and beside scattnlay, with each
// code's error against the 50-digit referee of the layered series.
//
// Particles: a soot core (1.75+0.44i) of half the outer radius under
// sulphate (1.43+1e-8i), and three layers (soot, 1.5+0.01i, sulphate at 0.3,
// 0.6 and 1 of the radius); outer x = 0.1 ... 1e4.  Columns, ns per call
// (one thread, thread CPU time, minimum over alternating blocks):
//   sphere        attenuvis::mie::sphere(x, sulphate): the baseline
//   layered       layered_sphere(), and its ratio to sphere()
//   batch         layered_spheres() on one thread over 256 particles of outer
//                 x in [0.98 x, x], per particle
//   scattnlay     scattnlay's nMie (double) per call, when given its library,
//                 and attenuvis layered / scattnlay
//   terms         the series terms attenuvis sums (scattnlay sums its own
//                 count, printed beside), and ns per term
//   error         largest of |q − q_ref|/max(|q_ref|, 1e-4 Qext_ref) over
//                 Qext, Qsca, Qback, g against the referee (x <= 1e3)
//
// Usage: mie_layered_speed [--quick] [--scattnlay LIB]
//   LIB  default build/scattnlay/libscattnlay_shim.so when present; build it
//        from your own scattnlay checkout with
//        validation/bench/scattnlay/build_scattnlay.sh /path/to/scattnlay
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../src/block_timing.hpp"  // the Mie benchmarks' one timing rule (private to validation/)
#include "attenuvis/mie.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/layered_referee.hpp"
#include "attenuvis/validation/mie_accuracy.hpp"
#include "attenuvis/validation/shared_library.hpp"

namespace {

namespace mie = attenuvis::mie;
namespace validation = attenuvis::validation;
using cd = std::complex<double>;
using ScattnlayEntry = int (*)(unsigned, const double*, const double*, double*);

struct Particle {
  std::string name;
  std::vector<double> fraction;  // outer radius of each layer / the particle's
  std::vector<cd> m;
};

struct Quantities {
  double qext, qsca, qback, g;
};

double error(const Quantities& q, const mie::Efficiencies<mie::Referee>& r) {
  const double ref[4] = {r.qext.convert_to<double>(), r.qsca.convert_to<double>(), r.qback.convert_to<double>(),
                         r.g.convert_to<double>()};
  const double got[4] = {q.qext, q.qsca, q.qback, q.g};
  double worst = 0;
  for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(got[k] - ref[k]) / std::max(std::abs(ref[k]), 1e-4 * ref[0]));
  return worst;
}

class Scattnlay {
 public:
  explicit Scattnlay(const std::string& path)
      : library_(path, "the scattnlay library", "attenuvis_scattnlay_efficiencies",
                 "validation/bench/scattnlay/build_scattnlay.sh") {}
  // Qext, Qsca, Qbk, g, and the terms (scattnlay's Qbk is B&H's, checked
  // against attenuvis on its own test cases: tests/data/mie/layered_scattnlay_nmie.csv).
  Quantities efficiencies(const std::vector<double>& x, const std::vector<cd>& m, int& terms) const {
    std::vector<double> re_im;
    for (const cd& v : m) re_im.push_back(v.real()), re_im.push_back(v.imag());
    double q[6] = {};
    terms = reinterpret_cast<ScattnlayEntry>(library_.entry())(static_cast<unsigned>(x.size()), x.data(),
                                                                re_im.data(), q);
    return {q[0], q[1], q[3], q[5]};
  }

 private:
  validation::SharedLibrary library_;
};

std::string default_library() {
  const std::string p = "build/scattnlay/libscattnlay_shim.so";
  return std::filesystem::exists(p) ? p : "";
}

void row(const Particle& p, double x, const Scattnlay* peer, double block_seconds) {
  namespace timing = attenuvis::validation::timing;
  std::vector<double> xs;
  for (double f : p.fraction) xs.push_back(f * x);
  // The batch: 256 particles with outer x from 0.98 x to x (one side of the
  // precision rule's x = 1e4, as the single call).
  constexpr std::size_t kBatch = 256;
  std::vector<double> bx;
  std::vector<cd> bm;
  std::vector<std::size_t> offsets = {0};
  for (std::size_t i = 0; i < kBatch; ++i) {
    const double s = 1 - 0.02 * static_cast<double>(i) / kBatch;
    for (std::size_t l = 0; l < xs.size(); ++l) bx.push_back(xs[l] * s), bm.push_back(p.m[l]);
    offsets.push_back(bx.size());
  }
  std::vector<mie::Efficiencies<double>> out(kBatch);
  mie::SpheresOptions one_thread;
  one_thread.threads = 1;
  const auto sphere = [&] { return mie::sphere(x, p.m.back()).qext; };
  const auto layered = [&] { return mie::layered_sphere(xs, p.m).qext; };
  const auto batch = [&] {
    mie::layered_spheres(offsets.data(), bx.data(), bm.data(), kBatch, out.data(), one_thread);
    return out[0].qext;
  };
  int peer_terms = 0;
  const auto scattnlay = [&] { return peer->efficiencies(xs, p.m, peer_terms).qext; };
  std::array<double, 4> ns{};
  if (peer) {
    ns = timing::alternating_min_ns(block_seconds, 5, sphere, layered, batch, scattnlay);
  } else {
    const auto three = timing::alternating_min_ns(block_seconds, 5, sphere, layered, batch);
    std::copy(three.begin(), three.end(), ns.begin());
    ns[3] = NAN;
  }
  ns[2] /= kBatch;
  const auto q = mie::layered_sphere(xs, p.m);
  const bool referee = x <= 1e3;
  double e_ours = NAN, e_peer = NAN;
  Quantities peer_q{};
  if (peer) peer_q = peer->efficiencies(xs, p.m, peer_terms);
  if (referee) {
    const auto r = mie::layered_sphere_referee(xs, p.m);
    e_ours = error({q.qext, q.qsca, q.qback, q.g}, r);
    if (peer) e_peer = error(peer_q, r);
  }
  std::printf("%-12s %8.3g %11.0f %11.0f %6.2f %11.0f %6.2f %11.0f %6.2f %6zu %6d %8.1f %9.1e %9.1e\n", p.name.c_str(),
              x, ns[0], ns[1], ns[1] / ns[0], ns[2], ns[2] / ns[0], ns[3], ns[1] / ns[3], q.terms, peer_terms,
              ns[1] / static_cast<double>(q.terms), e_ours, e_peer);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string library = default_library();
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--scattnlay") && i + 1 < argc) {
      library = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [--quick] [--scattnlay LIB]\n", argv[0]);
      return 2;
    }
  }
  std::unique_ptr<Scattnlay> peer;
  try {
    if (!library.empty()) peer = std::make_unique<Scattnlay>(library);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mie_layered_speed: %s\n", e.what());
    return 1;
  }
  std::printf("Layered spheres, ns per call on one thread (%s)\n", validation::timing_machine_description().c_str());
  std::printf("scattnlay: %s\n",
              peer ? library.c_str() : "not given (validation/bench/scattnlay/build_scattnlay.sh builds it)");
  std::printf("%-12s %8s %11s %11s %6s %11s %6s %11s %6s %6s %6s %8s %9s %9s\n", "particle", "outer x", "sphere",
              "layered", "/sph", "batch", "/sph", "scattnlay", "/snl", "terms", "snl", "ns/term", "err", "err snl");
  const std::vector<Particle> particles = {
      {"soot/sulph", {0.5, 1.0}, {{1.75, 0.44}, {1.43, 1e-8}}},
      {"3 layers", {0.3, 0.6, 1.0}, {{1.75, 0.44}, {1.5, 0.01}, {1.43, 1e-8}}}};
  const std::vector<double> xs = quick ? std::vector<double>{1, 100} : std::vector<double>{0.1, 1, 10, 100, 1e3, 1e4};
  for (const Particle& p : particles)
    for (double x : xs) row(p, x, peer.get(), quick ? 0.01 : 0.05);
  return 0;
}
