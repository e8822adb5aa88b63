#pragma once
/// The aggregator's configuration (litamin2-aggregator.yaml): DDS participant and topics, the
/// durable store, the mapper, ingest batching, publication policy, watchdog and logging, and its
/// validation (read from YAML by config/aggregator_config_yaml.hpp).

#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/service/security_config.hpp"
#include "litamin2/service/transport_config.hpp"
#include "litamin2/service/watchdog_config.hpp"

#include <string>

namespace litamin2::aggregator {

struct TopicsConfig {
  /// Input: the daemons' map patches (litamin2/msg/MapPatch).
  std::string map_patches = "rt/litamin2/map_patches";
  /// Output: corrected keyframe poses, one instance per stream (litamin2/msg/KeyframePoses).
  std::string keyframe_poses = "rt/litamin2/keyframe_poses";
  /// Output: the global map's summary (litamin2/msg/MapSummary).
  std::string map_summary = "rt/litamin2/map_summary";
  /// Output: the aggregator's status (diagnostic_msgs/DiagnosticArray).
  std::string status = "rt/litamin2/aggregator/status";
  /// Input: each stream's odometry (nav_msgs/Odometry), a pattern whose one '*' stands for the
  /// stream id; read for every stream seen in the map patches. Empty: no odometry is read and
  /// no map-frame odometry published.
  std::string odometry = "rt/*/odom";
  /// Output: each stream's current pose in the map frame (nav_msgs/Odometry, frame_id "map",
  /// child_frame_id as in its odometry), a pattern like `odometry`.
  std::string map_odometry = "rt/*/map_odom";
};

struct StoreConfig {
  /// The SQLite store (created if missing; a file that is not a keyframe store is refused).
  std::string path = "/var/lib/litamin2/aggregator.db";
  /// fsync at every commit (survives power loss; kill -9 is survived either way).
  bool synchronous_full = false;
};

struct IngestConfig {
  /// Patches queued between the DDS listener and the mapping thread; when full the listener
  /// waits (reliable DDS then holds the writers back) instead of dropping.
  int queue_capacity = 1024;
  /// At most this many patches are committed to the store in one transaction.
  int max_batch = 256;
};

struct PublishConfig {
  /// Corrected poses of streams that changed are published at most this often, seconds.
  double poses_period_s = 1.0;
  /// The map summary is rebuilt and published at most this often (when changed), seconds.
  double summary_period_s = 10.0;
  /// Voxel means listed in the summary at most (decimated evenly); 0 = counts only.
  int summary_max_means = 10000;
  /// Status period, seconds.
  double status_period_s = 1.0;
};

/// Bounds on what a client may send (docs/security.md, "Validation").
struct LimitsConfig {
  /// A map patch with more distributions is rejected (too_many_distributions) before any is
  /// converted; its serialised payload may be at most 40 bytes a distribution plus 1 MiB.
  int max_distributions_per_patch = 200'000;
};

struct AggregatorConfig {
  service::TransportConfig dds;
  /// DDS-Security (off by default).
  service::SecurityConfig security;
  LimitsConfig limits;
  TopicsConfig topics;
  StoreConfig store;
  IngestConfig ingest;
  PublishConfig publish;
  mapping::MapperConfig mapper;
  service::WatchdogConfig watchdog;
  /// spdlog level: trace, debug, info, warn, error, critical, off.
  std::string log_level = "info";
};

/// Throws ConfigError naming the key (as a dotted path) on the first invalid value: topics that
/// are not valid topic names or not distinct, odometry patterns without exactly one '*', an
/// empty store path, an unknown log level, an invalid mapper section.
void validate(const AggregatorConfig& config);

}  // namespace litamin2::aggregator
