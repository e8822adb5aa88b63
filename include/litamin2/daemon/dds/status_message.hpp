#pragma once
/// The daemon's status as a diagnostic_msgs/DiagnosticArray: one DiagnosticStatus per stream
/// (name "litamin2d: <stream>", hardware_id the stream id) with its rates, latencies and
/// counters as key/value pairs, published on rt/litamin2/status.

#include "diagnostic_msgs/msg/DiagnosticArray.h"
#include "litamin2/daemon/scan_merger.hpp"
#include "litamin2/daemon/stream_scheduler.hpp"
#include "litamin2/daemon/stream_stats.hpp"

#include <optional>
#include <string>
#include <vector>

namespace litamin2::daemon {

/// What the status reports about one stream.
struct StreamStatus {
  std::string id;
  std::string topic;
  StatsSnapshot stats;
  SchedulerCounters counters;
  /// A publisher was found and a reader created (reliable or best-effort).
  bool reading = false;
  bool reliable = false;
  std::uint64_t samples_lost = 0;
  /// A stream of several sensors: the merge's counters (scan_merger.hpp).
  std::optional<ScanMergerCounters> merge;
  /// Sharding: the member tracking the stream when it is not this daemon (the stream moved
  /// away); empty otherwise.
  std::string moved_to;
  /// 0 OK, 1 WARN (frames dropped or bad messages since the last status), 2 ERROR.
  std::uint8_t level = 0;
  std::string message = "ok";
};

/// The DiagnosticArray of `streams`, stamped `stamp` (the wall clock).
diagnostic_msgs::msg::DiagnosticArray make_status_message(const std::vector<StreamStatus>& streams,
                                                          Stamp stamp);

}  // namespace litamin2::daemon
