// Private to the reproduction job: what keeps its progress line (Progress,
// sections.hpp) saying what the job is doing while a step runs long.
//  - Heartbeat: progress of a long parallel loop whose workers must not write
//    to the terminal themselves.  Workers count finished items (done()); a
//    watcher thread reports "what: k of n, T s, about L s left" through the
//    job's progress line every `period`, and stops with the loop.
//  - ExternalProgress: a library prints its own line meanwhile.
//  - StallTicker: repeats a silent step's line with the time spent in it.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

#include "sections.hpp"

namespace attenuvis::validation::detail {

class Heartbeat {
 public:
  // `work` weighs the time-left estimate when items differ in cost (e.g. the
  // Mie terms of a cell); done(w) adds w of `total_work` units.
  Heartbeat(const Context& ctx, std::string section, std::string what, std::size_t items, double total_work,
            std::chrono::milliseconds period = std::chrono::milliseconds(2000));
  ~Heartbeat();
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

  void done(double work = 1.0);

 private:
  void run();

  const Context& ctx_;
  std::string section_, what_;
  std::size_t items_;
  double total_work_;
  std::chrono::milliseconds period_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<std::size_t> items_done_{0};
  std::mutex mutex_;
  double work_done_ = 0;
  bool stop_ = false;
  std::condition_variable wake_;
  std::thread thread_;
};

// While one is alive, a library prints its own progress line (visgraph's
// pairs done, rate and time left), and the job's ticker, which repeats a
// silent step's line, keeps quiet.
class ExternalProgress {
 public:
  ExternalProgress();
  ~ExternalProgress();
  ExternalProgress(const ExternalProgress&) = delete;
  ExternalProgress& operator=(const ExternalProgress&) = delete;
};
bool external_progress_active();

// While a step runs longer than a few seconds without saying anything (a
// sigma integral, a quadrature study), repeats its line with the time spent
// in it, so the user always sees what the job is doing.  Quiet while a
// library prints its own progress line (ExternalProgress).
class StallTicker {
 public:
  StallTicker(Progress& progress, bool enabled);
  ~StallTicker();
  StallTicker(const StallTicker&) = delete;
  StallTicker& operator=(const StallTicker&) = delete;

 private:
  void run();

  Progress& progress_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace attenuvis::validation::detail
