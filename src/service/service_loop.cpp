#include "litamin2/service/service_loop.hpp"

#include <spdlog/spdlog.h>

#include <csignal>

namespace litamin2::service {

ServiceLoop::ServiceLoop(bool watchdog_enabled)
    : notifier_(SdNotifier::from_environment()), watchdog_(notifier_, [&] {
        const auto interval = watchdog_interval_from_environment();
        return watchdog_enabled && interval ? *interval : std::chrono::microseconds(0);
      }()) {}

int ServiceLoop::run(ShutdownSignals& signals, const Hooks& hooks,
                     std::chrono::milliseconds period) {
  auto next_summary = Clock::now();
  int signal = 0;
  while ((signal = signals.wait_for(period)) == 0) {
    const auto now = Clock::now();
    if (!hooks.poll(now)) break;
    const bool healthy = hooks.healthy(now);
    if (!watchdog_.tick(healthy, now) && !healthy && watchdog_.enabled())
      spdlog::error("{}", hooks.stall_message);
    if (now >= next_summary) {
      notifier_.status(hooks.summary(now));
      next_summary = now + std::chrono::seconds(5);
    }
  }
  if (signal != 0)
    spdlog::info("{} received: shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
  return signal;
}

}  // namespace litamin2::service
