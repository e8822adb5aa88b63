#pragma once
/// What the metrics endpoint serves, handed over from the process's main loop to the HTTP
/// server's threads: the last rendered /metrics text, the time of the main loop's last turn
/// (/healthz) and whether the process is ready (/readyz). The main loop writes it from the
/// status it already computes; the server threads only read it, so they never touch a lock of
/// the tracking or mapping path. Thread-safe.

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>

namespace litamin2::service {

class MetricsBoard {
 public:
  using Clock = std::chrono::steady_clock;

  /// Replaces the /metrics text.
  void publish(std::string text);
  /// The last published text (empty before the first publish()).
  std::string text() const;

  /// The main loop turned at `now`.
  void beat(Clock::time_point now);
  /// The main loop turned within `max_age` of `now`, or has not begun yet (starting: the
  /// aggregator's store recovery may take minutes before its loop runs; systemd's watchdog too
  /// starts only at READY). A wedged start is /readyz's and TimeoutStartSec='s to report.
  bool alive(Clock::time_point now, Clock::duration max_age) const;

  void set_ready(bool ready) { ready_.store(ready); }
  bool ready() const { return ready_.load(); }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const std::string> text_;
  std::atomic<Clock::rep> last_beat_{0};
  std::atomic<bool> ready_{false};
};

}  // namespace litamin2::service
