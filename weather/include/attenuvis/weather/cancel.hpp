// Stopping a long weather computation from another thread (a Ctrl-C in the
// Python bindings, a GUI's stop button): the caller owns a flag, hands it in
// through Settings::cancel, and sets it; the quadratures look at it once per
// panel (a batch of Mie evaluations) and the sigma table once per cell.
#pragma once

#include <atomic>
#include <stdexcept>

namespace attenuvis::weather {

// Thrown when the caller's cancel flag is set: a requested stop, not a
// failure.  Nothing partial is returned or memoised.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("weather computation cancelled") {}
};

// Throws Cancelled when `cancel` is set; no flag (nullptr) never cancels.
inline void throw_if_cancelled(const std::atomic<bool>* cancel) {
  if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) throw Cancelled();
}

}  // namespace attenuvis::weather
