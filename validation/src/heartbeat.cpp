// Progress of long loops inside the reproduction job (heartbeat.hpp).
#include "heartbeat.hpp"

#include <cstdio>

namespace attenuvis::validation::detail {

Heartbeat::Heartbeat(const Context& ctx, std::string section, std::string what, std::size_t items, double total_work,
                     std::chrono::milliseconds period)
    : ctx_(ctx),
      section_(std::move(section)),
      what_(std::move(what)),
      items_(items),
      total_work_(total_work),
      period_(period),
      start_(std::chrono::steady_clock::now()) {
  if (ctx_.progress) thread_ = std::thread([this] { run(); });
}

Heartbeat::~Heartbeat() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Heartbeat::done(double work) {
  items_done_.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(mutex_);
  work_done_ += work;
}

void Heartbeat::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, period_, [this] { return stop_; })) {
    const double t = seconds_since(start_);
    char line[160];
    // Time left from the work done so far (items differ in cost; the work
    // units say by how much), once enough is done for the rate to mean
    // something: early on, finished items are the cheap ones.
    if (work_done_ >= 0.2 * total_work_ && work_done_ < total_work_)
      std::snprintf(line, sizeof line, ": %zu of %zu done, %.0f s, about %.0f s left",
                    items_done_.load(std::memory_order_relaxed), items_, t, t * (total_work_ - work_done_) / work_done_);
    else
      std::snprintf(line, sizeof line, ": %zu of %zu done, %.0f s", items_done_.load(std::memory_order_relaxed), items_, t);
    ctx_.step(section_, what_ + line);
  }
}

namespace {
std::atomic<int> external_progress{0};
}  // namespace

ExternalProgress::ExternalProgress() { external_progress.fetch_add(1); }
ExternalProgress::~ExternalProgress() { external_progress.fetch_sub(1); }
bool external_progress_active() { return external_progress.load() > 0; }

}  // namespace attenuvis::validation::detail
