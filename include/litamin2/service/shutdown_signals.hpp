#pragma once
/// SIGTERM/SIGINT as a request for graceful shutdown: the signals are blocked in every thread
/// and collected synchronously by the main loop (no async-signal handler runs daemon code).

#include <chrono>
#include <csignal>

namespace litamin2::service {

class ShutdownSignals {
 public:
  /// Blocks SIGTERM and SIGINT in the calling thread. Threads started afterwards inherit the
  /// mask, so construct this in main() before any other thread exists (DDS, TBB, logging).
  ShutdownSignals();
  /// Restores the previous signal mask of the calling thread.
  ~ShutdownSignals();
  ShutdownSignals(const ShutdownSignals&) = delete;
  ShutdownSignals& operator=(const ShutdownSignals&) = delete;

  /// Waits up to `timeout` for SIGTERM or SIGINT; returns the signal number, or 0 on timeout.
  int wait_for(std::chrono::milliseconds timeout);

 private:
  sigset_t signals_{};
  sigset_t previous_{};
};

}  // namespace litamin2::service
