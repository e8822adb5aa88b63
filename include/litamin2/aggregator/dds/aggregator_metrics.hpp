#pragma once
/// litamin2-aggregator's /metrics text (Prometheus exposition format 0.0.4) from what its status
/// (rt/litamin2/aggregator/status) already reports: keyframes (total and per stream), loops,
/// merges, optimisations and their wall-time histogram, full passes, duplicates, patches
/// received and rejected by reason, malformed and lost samples, queue depth, map tiles, the
/// store's size on disk, and each stream's odometry relay. docs/deploy.md lists them.

#include "litamin2/aggregator/dds/aggregator_messages.hpp"
#include "litamin2/aggregator/dds/map_odometry_relay.hpp"
#include "litamin2/aggregator/mapping_worker.hpp"

#include <cstdint>
#include <map>
#include <string>

namespace litamin2::aggregator {

/// Every metric, with litamin2_build_info{program="litamin2-aggregator",version=...} 1.
std::string aggregator_metrics_text(const WorkerStatus& worker, const IngestCounters& ingest,
                                    const std::map<std::string, OdometryStreamStatus>& odometry,
                                    std::uint64_t store_bytes);

/// The SQLite store's bytes on disk: the file and its write-ahead log (0 for what is missing).
std::uint64_t store_size_bytes(const std::string& path);

}  // namespace litamin2::aggregator
