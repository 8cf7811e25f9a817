// Progress of a long pass: pairs done (cast, or decided by culling), rate
// and time left, sampled once a second from the first second by a watcher
// thread.  It goes to the caller's callback (VisibilityOptions::on_progress)
// and, when asked, to stderr: "<label>: NN% of P pairs, R M pairs/s, T s,
// about L s left", rewritten in place on a terminal, one line a second
// otherwise (logs).
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace attenuvis::visgraph {

class Progress {
 public:
  Progress(bool print, std::function<void(const ProgressReport&)> callback, std::uint64_t total, std::string label);
  ~Progress();
  void add(std::uint64_t done) { done_.fetch_add(done, std::memory_order_relaxed); }
  void finish();

 private:
  void run();
  ProgressReport report(double seconds) const;
  bool print_;
  std::function<void(const ProgressReport&)> callback_;
  std::uint64_t total_;
  std::string label_;
  std::atomic<std::uint64_t> done_{0};
  bool stop_ = false;
  bool printed_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace attenuvis::visgraph
