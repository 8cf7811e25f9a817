// Long C++ work that Ctrl-C can stop.
//
// The work runs on a worker thread with the GIL released; the calling thread
// wakes every 0.1 s, takes the GIL, checks for signals (Ctrl-C ->
// KeyboardInterrupt) and calls `tick` (a progress callback, say).  An
// exception from either sets `cancel`, which the work polls (a visibility
// pass between rows, a weather quadrature once per panel); the worker is
// joined and the exception goes on to Python, so nothing is left running and
// no partial result is returned.  Without an interruption the work's own
// result or exception comes back unchanged.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace attenuvis::python {

// Called with the GIL held; returns work()'s result.
template <class Work, class Tick>
auto watched_call(Work work, std::atomic<bool>& cancel, Tick tick) -> decltype(work()) {
  namespace py = pybind11;
  std::optional<decltype(work())> result;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread([&] {
      try {
        result.emplace(work());
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      finished_cv.notify_all();
    });
  }
  auto stop = [&] {
    cancel = true;
    py::gil_scoped_release release;
    worker.join();
  };
  try {
    for (;;) {
      bool is_finished;
      {
        py::gil_scoped_release release;
        std::unique_lock<std::mutex> lock(mutex);
        is_finished = finished_cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; });
      }
      if (is_finished) break;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      tick();
    }
  } catch (...) {
    stop();  // the work's own outcome (Cancelled, or a result) is dropped
    throw;
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

// The same without a tick.
template <class Work>
auto watched_call(Work work, std::atomic<bool>& cancel) -> decltype(work()) {
  return watched_call(std::move(work), cancel, [] {});
}

}  // namespace attenuvis::python
