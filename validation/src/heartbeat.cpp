// The reproduction job's progress line and what keeps it alive while a step
// runs long (heartbeat.hpp).
#include "heartbeat.hpp"

#include <cstdio>
#include <ostream>

namespace attenuvis::validation::detail {

namespace {

// What the progress line last said and when, shared by the steps and the
// ticker that repeats it while a step runs long (Progress's own members are
// per object; there is one job and one line).
struct LineState {
  std::mutex mutex;
  std::string section, what;
  std::string repeat;  // the ticker's repetition of `what`, not a new step
  std::chrono::steady_clock::time_point since, last_print;
};
LineState& line_state() {
  static LineState state;
  return state;
}

}  // namespace

Progress::Progress(std::ostream* os, bool tty) : os_(os), tty_(tty), start_(std::chrono::steady_clock::now()) {}

double Progress::elapsed() const { return seconds_since(start_); }

void Progress::step(const std::string& section, const std::string& what) {
  if (!os_) return;
  LineState& line = line_state();
  std::lock_guard<std::mutex> lock(line.mutex);
  char t[32];
  std::snprintf(t, sizeof t, "%6.1f s", elapsed());
  if (tty_) *os_ << "\r\033[K";
  *os_ << "reproduce [" << t << "] " << section << ": " << what;
  if (!tty_) *os_ << "\n";
  os_->flush();
  line.last_print = std::chrono::steady_clock::now();
  if (what == line.repeat) return;
  if (section != line.section || what != line.what) line.since = line.last_print;
  line.section = section;
  line.what = what;
}

void Progress::done() {
  if (os_ && tty_) *os_ << "\r\033[K";
  if (os_) os_->flush();
}

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

StallTicker::StallTicker(Progress& progress, bool enabled) : progress_(progress) {
  if (enabled) thread_ = std::thread([this] { run(); });
}

StallTicker::~StallTicker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StallTicker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) {
    std::string section, what;
    double in_step = 0;
    {
      LineState& line = line_state();
      std::lock_guard<std::mutex> l(line.mutex);
      if (line.section.empty() || seconds_since(line.last_print) < 3.0 || external_progress_active()) continue;
      section = line.section, what = line.what, in_step = seconds_since(line.since);
      char t[48];
      std::snprintf(t, sizeof t, " (working, %.0f s in this step)", in_step);
      line.repeat = what + t;
      what = line.repeat;
    }
    progress_.step(section, what);
  }
}

}  // namespace attenuvis::validation::detail
