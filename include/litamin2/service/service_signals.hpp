#pragma once
/// The signals a service acts on: SIGTERM and SIGINT (graceful shutdown) and SIGHUP (reload the
/// configuration). They are blocked in every thread and collected synchronously by the main
/// loop (no async-signal handler runs service code).

#include <chrono>
#include <csignal>

namespace litamin2::service {

class ServiceSignals {
 public:
  /// Blocks SIGTERM, SIGINT and SIGHUP in the calling thread. Threads started afterwards inherit
  /// the mask, so construct this in main() before any other thread exists (DDS, TBB, logging).
  ServiceSignals();
  /// Restores the previous signal mask of the calling thread.
  ~ServiceSignals();
  ServiceSignals(const ServiceSignals&) = delete;
  ServiceSignals& operator=(const ServiceSignals&) = delete;

  /// Waits up to `timeout` for SIGTERM, SIGINT or SIGHUP; returns the signal number, or 0 on
  /// timeout.
  int wait_for(std::chrono::milliseconds timeout);

 private:
  sigset_t signals_{};
  sigset_t previous_{};
};

}  // namespace litamin2::service
