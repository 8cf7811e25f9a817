// Many layered spheres in one call: see attenuvis/mie/layered.hpp.
#include <limits>

#include "attenuvis/mie/layered.hpp"
#include "layered_checks.hpp"
#include "shared_items.hpp"

namespace attenuvis::mie {

std::vector<SphereError> layered_spheres(const std::size_t* offsets, const double* x, const std::complex<double>* m,
                                         std::size_t count, Efficiencies<double>* out, const SpheresOptions& options) {
  std::vector<SphereError> errors;
  std::vector<std::size_t> good;
  good.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t first = offsets[i], layers = offsets[i + 1] - offsets[i];
    const std::string e = detail::layered_error(x + first, m + first, layers, 0);
    if (e.empty()) {
      good.push_back(i);
      continue;
    }
    errors.push_back({i, e});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out[i] = Efficiencies<double>{nan, nan, nan, nan, nan, nan, 0};
  }
  // Particles differ in cost by orders of magnitude (x, layers, precision).
  detail::share_items(good.size(), options.threads, [&](std::size_t k) {
    const std::size_t i = good[k], first = offsets[i];
    out[i] = detail::layered_evaluate(x + first, m + first, offsets[i + 1] - first, false, Extras{}, options.options).q;
  });
  return errors;
}

}  // namespace attenuvis::mie
