#pragma once
/// The `watchdog:` section of both processes' configs.

namespace litamin2::service {

/// The systemd watchdog: WATCHDOG=1 is sent (at half of $WATCHDOG_USEC) only while no unit of
/// work (a frame, a batch of patches) has been in processing for longer than stall_timeout_s,
/// so a wedged service is restarted.
struct WatchdogConfig {
  bool enabled = true;
  double stall_timeout_s = 10.0;
};

}  // namespace litamin2::service
