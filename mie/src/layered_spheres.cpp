// Many layered spheres in one call: see attenuvis/mie/layered.hpp.
#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <thread>

#include "attenuvis/mie/layered.hpp"
#include "layered_checks.hpp"

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
  // Particles differ in cost by orders of magnitude (x, layers, precision):
  // threads take the next one from a shared counter.
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(1, good.size() / 4)));
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  const auto worker = [&] {
    try {
      for (std::size_t k; (k = next.fetch_add(1)) < good.size();) {
        const std::size_t i = good[k], first = offsets[i];
        out[i] = detail::layered_evaluate(x + first, m + first, offsets[i + 1] - first, false, Extras{},
                                          options.options)
                     .q;
      }
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return errors;
}

}  // namespace attenuvis::mie
