// Work items shared out over threads, each thread taking the next item from a
// shared counter: for items whose costs differ by orders of magnitude (the
// spheres and lane groups of spheres(), the particles of layered_spheres()),
// where a fixed split would leave threads idle.  Private to the mie library.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace attenuvis::mie::detail {

// work(k) for k = 0 .. items − 1, in increasing k per thread, on up to
// `threads` threads (0: every core), no more than one per four items (a
// thread for fewer costs more than it saves).  The first exception any item
// throws is rethrown here once all threads have stopped taking items.
template <class Work>
void share_items(std::size_t items, unsigned threads, const Work& work) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(1, items / 4)));
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  const auto worker = [&] {
    try {
      for (std::size_t k; !failed.load(std::memory_order_relaxed) && (k = next.fetch_add(1)) < items;) work(k);
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
}

}  // namespace attenuvis::mie::detail
