// Progress of a long pass: pairs done (cast, or decided by culling), rate
// and time left, sampled once a second from the first second by a watcher
// thread.  It goes to the caller's callback (VisibilityOptions::on_progress)
// and, when asked, to stderr: "<label>: NN% of P pairs, R M pairs/s, T s,
// about L s left", rewritten in place on a terminal, one line a second
// otherwise (logs).  A caller watching from another thread (the Python
// binding) may also pass a counter to mirror the pairs into and a cancel flag:
// once that reads true, the next add() throws Cancelled, which ends the pass
// on every path (rays, culling) within one row or cluster pair.
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
  Progress(bool print, std::function<void(const ProgressReport&)> callback, std::uint64_t total, std::string label,
           std::atomic<std::uint64_t>* mirror = nullptr, const std::atomic<bool>* cancel = nullptr);
  ~Progress();
  void add(std::uint64_t done) {
    if (scale_ != 1.0) done = static_cast<std::uint64_t>(static_cast<double>(done) * scale_ + 0.5);
    done_.fetch_add(done, std::memory_order_relaxed);
    if (mirror_) mirror_->fetch_add(done, std::memory_order_relaxed);
    if (cancel_ && cancel_->load(std::memory_order_relaxed)) throw Cancelled();
  }
  void finish();
  // A process that computes one share of a pass (PassShare) counts its own
  // pairs times `scale` (the whole pass's pairs over its share's), so that
  // its line estimates the whole pass.  Set before the workers add.
  void set_scale(double scale) { scale_ = scale; }

 private:
  void run();
  ProgressReport report(double seconds) const;
  bool print_;
  std::function<void(const ProgressReport&)> callback_;
  std::uint64_t total_;
  std::string label_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::uint64_t>* mirror_;
  const std::atomic<bool>* cancel_;
  double scale_ = 1.0;
  bool stop_ = false;
  bool printed_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace attenuvis::visgraph
