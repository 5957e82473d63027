// Ctrl-C during a long call of the core (run, tolerance, range, a sweep variant):
// the core asks its InterruptPoll between steps and runs (analysis/kinematic_analysis.hpp);
// the binding only forwards Python's answer. On the thread that made the call (Python
// runs signal handlers on the main thread only) the poll takes the GIL at most every
// 20 ms and lets Python run its handlers (PyErr_CheckSignals); a raised exception
// (KeyboardInterrupt) stops the core and RethrowIfRaised re-raises it. Threads of a
// sweep's pool see the process-wide flag RequestStopAll (set by mechkin.sweep when
// its waiting main thread is interrupted).
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "analysis/kinematic_analysis.hpp"

namespace mechkin_python {

inline std::atomic<bool>& StopAllFlag() {
  static std::atomic<bool> flag{false};
  return flag;
}

class PythonInterrupt {
 public:
  PythonInterrupt() : state_(std::make_shared<State>()) { state_->caller = std::this_thread::get_id(); }

  mechkin::InterruptPoll Poll() const {
    std::shared_ptr<State> s = state_;
    return [s] {
      if (s->raised.load() || StopAllFlag().load()) return true;
      if (std::this_thread::get_id() != s->caller) return false;
      const auto now = std::chrono::steady_clock::now();
      if (now - s->last_check < std::chrono::milliseconds(20)) return false;
      s->last_check = now;  // only the caller's thread writes it
      pybind11::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) s->raised = true;  // the exception stays set on this thread
      return s->raised.load();
    };
  }
  /// With the GIL, after the core returned: the exception a handler raised, if any.
  void RethrowIfRaised() const {
    if (state_->raised.load() && PyErr_Occurred()) throw pybind11::error_already_set();
  }

 private:
  struct State {
    std::thread::id caller;
    std::chrono::steady_clock::time_point last_check{};
    std::atomic<bool> raised{false};
  };
  std::shared_ptr<State> state_;
};

}  // namespace mechkin_python
