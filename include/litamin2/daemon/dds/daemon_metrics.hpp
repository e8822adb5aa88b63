#pragma once
/// litamin2d's /metrics text (Prometheus exposition format 0.0.4) from the per-stream status the
/// daemon already computes for rt/litamin2/status (DaemonNode::status): counters of frames
/// received, processed, dropped, failed, unregistered, out of order, bad messages by reason,
/// samples lost, keyframes; the arrival-to-odometry latency histogram; queue depth and map size.
/// docs/deploy.md lists them.

#include "litamin2/daemon/dds/status_message.hpp"

#include <string>
#include <vector>

namespace litamin2::daemon {

/// Every metric for `streams`, with litamin2_build_info{program="litamin2d",version=...} 1.
std::string daemon_metrics_text(const std::vector<StreamStatus>& streams);

}  // namespace litamin2::daemon
