#include "litamin2/service/service_loop.hpp"

#include <spdlog/spdlog.h>

#include <csignal>
#include <ctime>
#include <string>

namespace litamin2::service {

ServiceLoop::ServiceLoop(bool watchdog_enabled)
    : notifier_(SdNotifier::from_environment()), watchdog_(notifier_, [&] {
        const auto interval = watchdog_interval_from_environment();
        return watchdog_enabled && interval ? *interval : std::chrono::microseconds(0);
      }()) {}

void ServiceLoop::reload(const Hooks& hooks) {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  const long long usec = static_cast<long long>(now.tv_sec) * 1000000 + now.tv_nsec / 1000;
  notifier_.notify("RELOADING=1\nMONOTONIC_USEC=" + std::to_string(usec));
  if (hooks.reload) {
    spdlog::info("SIGHUP received: reloading the configuration");
    hooks.reload();
  } else {
    spdlog::info("SIGHUP received: nothing to reload");
  }
  notifier_.ready();
}

int ServiceLoop::run(ServiceSignals& signals, const Hooks& hooks,
                     std::chrono::milliseconds period) {
  auto next_summary = Clock::now();
  int signal = 0;
  while ((signal = signals.wait_for(period)) == 0 || signal == SIGHUP) {
    if (signal == SIGHUP) reload(hooks);
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
