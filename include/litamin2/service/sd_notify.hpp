#pragma once
/// systemd notifications through libsystemd (sd_notify(3): datagrams such as "READY=1" to the
/// socket named by $NOTIFY_SOCKET) and the watchdog pinger that keeps a Type=notify service with
/// WatchdogSec= alive (sd_watchdog_enabled(3)).

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace litamin2::service {

class SdNotifier {
 public:
  /// A notifier that sends nothing (not run by systemd).
  SdNotifier() = default;
  /// The notifier for $NOTIFY_SOCKET (disabled if unset or empty). libsystemd reads the
  /// variable again on every send, so it must stay set while the notifier is used.
  static SdNotifier from_environment();

  /// There is a socket to send to.
  bool enabled() const { return !socket_.empty(); }
  /// $NOTIFY_SOCKET as it was when the notifier was made.
  const std::string& socket() const { return socket_; }

  /// Sends one datagram ("KEY=VALUE" lines) with sd_notify(). Returns false if disabled or the
  /// send failed (e.g. nobody listens).
  bool notify(std::string_view message) const;
  bool ready() const { return notify("READY=1"); }
  bool watchdog() const { return notify("WATCHDOG=1"); }
  bool stopping() const { return notify("STOPPING=1"); }
  /// STATUS=<text> (newlines replaced by spaces).
  bool status(std::string_view text) const;

 private:
  explicit SdNotifier(std::string socket) : socket_(std::move(socket)) {}
  std::string socket_;
};

/// The watchdog interval systemd expects pings within, from sd_watchdog_enabled(): set when
/// $WATCHDOG_USEC is a positive number and $WATCHDOG_PID is unset or this process's pid;
/// nothing otherwise (also for an invalid value).
std::optional<std::chrono::microseconds> watchdog_interval_from_environment();

/// Sends WATCHDOG=1 at half the watchdog interval, but only while the daemon reports itself
/// healthy: tick() is called from the processing loop, so a loop that stops turning (or a
/// stalled stream, reported as unhealthy) stops the pings and systemd restarts the service.
class WatchdogPinger {
 public:
  using Clock = std::chrono::steady_clock;

  /// Pings `notifier` every `interval / 2`; a zero interval disables pinging.
  WatchdogPinger(const SdNotifier& notifier, std::chrono::microseconds interval);

  /// Sends a ping if one is due and `healthy`; returns true if it sent one.
  bool tick(bool healthy, Clock::time_point now = Clock::now());

  bool enabled() const { return period_.count() > 0 && notifier_.enabled(); }
  std::chrono::microseconds period() const { return period_; }
  /// Pings sent so far.
  std::size_t pings() const { return pings_; }

 private:
  const SdNotifier& notifier_;
  std::chrono::microseconds period_;
  std::optional<Clock::time_point> last_;
  std::size_t pings_ = 0;
};

}  // namespace litamin2::service
