#include "progress.hpp"

#include <chrono>
#include <cstdio>

#include <unistd.h>

namespace attenuvis::visgraph {

Progress::Progress(bool enabled, std::uint64_t total, std::string label) : total_(total), label_(std::move(label)) {
  if (enabled) thread_ = std::thread([this] { run(); });
}

Progress::~Progress() { finish(); }

void Progress::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Progress::run() {
  const auto start = std::chrono::steady_clock::now();
  const bool tty = ::isatty(::fileno(stderr)) != 0;
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_for(lock, std::chrono::seconds(3), [this] { return stop_; })) return;
  while (true) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto done = done_.load(std::memory_order_relaxed);
    const double fraction = total_ ? static_cast<double>(done) / total_ : 1.0;
    const double rate = seconds > 0 ? done / seconds : 0.0;  // pairs/s so far
    char left[48] = "time left unknown";
    if (rate > 0 && done < total_) std::snprintf(left, sizeof left, "about %.0f s left", (total_ - done) / rate);
    std::fprintf(stderr, "%s%s: %5.1f%% of %llu pairs, %.3g M pairs/s, %.0f s, %s%s", tty ? "\r\033[K" : "",
                 label_.c_str(), 100.0 * fraction, static_cast<unsigned long long>(total_), rate / 1e6, seconds, left,
                 tty ? "" : "\n");
    std::fflush(stderr);
    printed_ = true;
    if (wake_.wait_for(lock, std::chrono::seconds(tty ? 1 : 5), [this] { return stop_; })) break;
  }
  if (printed_ && tty) std::fprintf(stderr, "\n");
}

}  // namespace attenuvis::visgraph
