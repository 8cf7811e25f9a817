// A progress line on stderr for long passes: silent for the first 3 s, then
// "<label>: NN% of P pairs, R M pairs/s, T s, about L s left" -- rewritten in
// place once a second on a terminal, one line every 5 s otherwise (logs).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace attenuvis::visgraph {

class Progress {
 public:
  Progress(bool enabled, std::uint64_t total, std::string label);
  ~Progress();
  void add(std::uint64_t done) { done_.fetch_add(done, std::memory_order_relaxed); }
  void finish();

 private:
  void run();
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
