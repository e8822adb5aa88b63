#pragma once
/// The systemd side of a Type=notify service's main loop, shared by litamin2d and
/// litamin2-aggregator: notifications to $NOTIFY_SOCKET, the watchdog of $WATCHDOG_USEC
/// (pinged only while the service reports itself healthy) and a STATUS every 5 s.

#include "litamin2/service/sd_notify.hpp"
#include "litamin2/service/service_signals.hpp"

#include <chrono>
#include <functional>
#include <string>

namespace litamin2::service {

class ServiceLoop {
 public:
  using Clock = std::chrono::steady_clock;

  /// What the loop asks the service at every turn.
  struct Hooks {
    /// Does the periodic work; returning false ends the loop (without a signal).
    std::function<bool(Clock::time_point)> poll;
    /// The watchdog is withheld while this is false.
    std::function<bool(Clock::time_point)> healthy;
    /// The STATUS text.
    std::function<std::string(Clock::time_point)> summary;
    /// Logged as an error at every turn the watchdog is withheld.
    std::string stall_message;
    /// Called on SIGHUP, between RELOADING=1 and READY=1 (may be empty: nothing to reload).
    std::function<void()> reload;
  };

  /// The notifier of $NOTIFY_SOCKET; the watchdog pings only if `watchdog_enabled` (the
  /// config's watchdog.enabled) and $WATCHDOG_USEC is set.
  explicit ServiceLoop(bool watchdog_enabled);
  ServiceLoop(const ServiceLoop&) = delete;
  ServiceLoop& operator=(const ServiceLoop&) = delete;

  const SdNotifier& notifier() const { return notifier_; }
  const WatchdogPinger& watchdog() const { return watchdog_; }

  /// Turns every `period` (a STATUS at the first turn, then every 5 s) until SIGTERM or SIGINT
  /// arrives (logged and returned) or hooks.poll returns false (returns 0). SIGHUP runs
  /// hooks.reload, framed by RELOADING=1 (with MONOTONIC_USEC, as systemd's reload protocol
  /// asks) and READY=1, and the loop goes on.
  int run(ServiceSignals& signals, const Hooks& hooks, std::chrono::milliseconds period);

 private:
  void reload(const Hooks& hooks);

  SdNotifier notifier_;
  WatchdogPinger watchdog_;
};

}  // namespace litamin2::service
