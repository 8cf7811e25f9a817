#include "progress.hpp"

#include <chrono>
#include <cstdio>

#include <unistd.h>

namespace attenuvis::visgraph {

Progress::Progress(bool print, std::function<void(const ProgressReport&)> callback, std::uint64_t total,
                   std::string label, std::atomic<std::uint64_t>* mirror, const std::atomic<bool>* cancel)
    : print_(print), callback_(std::move(callback)), total_(total), label_(std::move(label)), mirror_(mirror),
      cancel_(cancel) {
  if (print_ || callback_) thread_ = std::thread([this] { run(); });
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

ProgressReport Progress::report(double seconds) const {
  ProgressReport r;
  r.pairs_total = total_;
  r.pairs_done = std::min(done_.load(std::memory_order_relaxed), total_);
  r.seconds = seconds;
  r.pairs_per_s = seconds > 0 ? static_cast<double>(r.pairs_done) / seconds : 0.0;
  r.seconds_left = r.pairs_per_s > 0 ? static_cast<double>(total_ - r.pairs_done) / r.pairs_per_s : -1.0;
  return r;
}

void Progress::run() {
  const auto start = std::chrono::steady_clock::now();
  const bool tty = ::isatty(::fileno(stderr)) != 0;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) {
    const ProgressReport r =
        report(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (callback_) callback_(r);
    if (!print_) continue;
    char left[48] = "time left unknown";
    if (r.seconds_left >= 0 && r.pairs_done < r.pairs_total)
      std::snprintf(left, sizeof left, "about %.0f s left", r.seconds_left);
    std::fprintf(stderr, "%s%s: %5.1f%% of %llu pairs (%llu done), %.3g M pairs/s, %.0f s, %s%s", tty ? "\r\033[K" : "",
                 label_.c_str(), r.pairs_total ? 100.0 * r.pairs_done / r.pairs_total : 100.0,
                 static_cast<unsigned long long>(r.pairs_total), static_cast<unsigned long long>(r.pairs_done),
                 r.pairs_per_s / 1e6, r.seconds, left, tty ? "" : "\n");
    std::fflush(stderr);
    printed_ = true;
  }
  if (printed_ && tty) std::fprintf(stderr, "\n");
}

}  // namespace attenuvis::visgraph
