#pragma once
/// A minimal systemd notification client (the sd_notify protocol: datagrams such as "READY=1"
/// to the unix socket named by $NOTIFY_SOCKET, '@' for the abstract namespace) and the
/// watchdog pinger that keeps a Type=notify service with WatchdogSec= alive.

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace litamin2::service {

class SdNotifier {
 public:
  /// A notifier that sends nothing (not run by systemd).
  SdNotifier() = default;
  /// A notifier for the socket `path` ("/run/systemd/notify", or "@name" for an abstract
  /// socket); an empty path gives a disabled notifier.
  explicit SdNotifier(std::string path);
  /// The notifier for $NOTIFY_SOCKET (disabled if unset or empty).
  static SdNotifier from_environment();
  ~SdNotifier();
  SdNotifier(SdNotifier&& other) noexcept;
  SdNotifier& operator=(SdNotifier&& other) noexcept;
  SdNotifier(const SdNotifier&) = delete;
  SdNotifier& operator=(const SdNotifier&) = delete;

  /// There is a socket to send to.
  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }

  /// Sends one datagram ("KEY=VALUE" lines). Returns false if disabled or the send failed;
  /// never blocks.
  bool notify(std::string_view message) const;
  bool ready() const { return notify("READY=1"); }
  bool watchdog() const { return notify("WATCHDOG=1"); }
  bool stopping() const { return notify("STOPPING=1"); }
  /// STATUS=<text> (newlines replaced by spaces).
  bool status(std::string_view text) const;

 private:
  std::string path_;
  int fd_ = -1;
};

/// The watchdog interval systemd expects pings within: $WATCHDOG_USEC, if set to a positive
/// number and $WATCHDOG_PID is unset or this process's pid.
std::optional<std::chrono::microseconds> watchdog_interval_from_environment();
/// Parses a WATCHDOG_USEC value (a positive decimal integer); nothing if invalid.
std::optional<std::chrono::microseconds> parse_watchdog_usec(const char* text);

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
