#include "progress.hpp"

#include <chrono>
#include <cstdio>

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
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_for(lock, std::chrono::seconds(3), [this] { return stop_; })) return;
  while (true) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double fraction = total_ ? static_cast<double>(done_.load(std::memory_order_relaxed)) / total_ : 1.0;
    std::fprintf(stderr, "\r%s: %5.1f%% of %llu pairs, %.0f s", label_.c_str(), 100.0 * fraction,
                 static_cast<unsigned long long>(total_), seconds);
    std::fflush(stderr);
    printed_ = true;
    if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) break;
  }
  if (printed_) std::fprintf(stderr, "\n");
}

}  // namespace attenuvis::visgraph
