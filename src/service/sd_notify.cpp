#include "litamin2/service/sd_notify.hpp"

#include <systemd/sd-daemon.h>

#include <cstdint>
#include <cstdlib>

namespace litamin2::service {

SdNotifier SdNotifier::from_environment() {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  return SdNotifier(socket ? std::string(socket) : std::string());
}

bool SdNotifier::notify(std::string_view message) const {
  if (!enabled()) return false;
  // sd_notify: > 0 sent, 0 no $NOTIFY_SOCKET, < 0 -errno.
  return sd_notify(0, std::string(message).c_str()) > 0;
}

bool SdNotifier::status(std::string_view text) const {
  std::string message = "STATUS=";
  message.append(text);
  for (char& c : message)
    if (c == '\n') c = ' ';
  return notify(message);
}

std::optional<std::chrono::microseconds> watchdog_interval_from_environment() {
  std::uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) <= 0 || usec == 0) return std::nullopt;
  return std::chrono::microseconds(static_cast<std::chrono::microseconds::rep>(usec));
}

WatchdogPinger::WatchdogPinger(const SdNotifier& notifier, std::chrono::microseconds interval)
    : notifier_(notifier), period_(interval / 2) {}

bool WatchdogPinger::tick(bool healthy, Clock::time_point now) {
  if (!enabled() || !healthy) return false;
  if (last_ && now - *last_ < period_) return false;
  last_ = now;
  if (!notifier_.watchdog()) return false;
  ++pings_;
  return true;
}

}  // namespace litamin2::service
