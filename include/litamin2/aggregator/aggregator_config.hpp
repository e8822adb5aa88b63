#pragma once
/// The aggregator's configuration (litamin2-aggregator.yaml): DDS participant and topics, the
/// durable store, the mapper, ingest batching, publication policy, watchdog and logging, and its
/// validation (read from YAML by config/aggregator_config_yaml.hpp).

#include "litamin2/aggregator/full_pass_worker.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/tile_map.hpp"
#include "litamin2/service/metrics_config.hpp"
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
  /// Output: the map tiles that changed, one instance per tile (litamin2/msg/MapTile).
  std::string map_tiles = "rt/litamin2/map_tiles";
  /// Output: the aggregator's status (diagnostic_msgs/DiagnosticArray).
  std::string status = "rt/litamin2/aggregator/status";
  /// The same status also here: ROS 2's /diagnostics, with diagnostic_updater's QoS. Empty:
  /// only on `status`.
  std::string diagnostics = "rt/diagnostics";
  /// Input: each stream's odometry (nav_msgs/Odometry), a pattern whose one '*' stands for the
  /// stream id; read for every stream seen in the map patches. Empty: no odometry is read and
  /// no map-frame odometry published.
  std::string odometry = "rt/*/odom";
  /// Output: each stream's current pose in the map frame (nav_msgs/Odometry, frame_id "map",
  /// child_frame_id as in its odometry), a pattern like `odometry`.
  std::string map_odometry = "rt/*/map_odom";
  /// Output: each stream's map -> odom transform (tf2_msgs/TFMessage, parent "map", child the
  /// odometry's frame_id) when its correction changes and with each map-frame pose. Empty:
  /// none.
  std::string tf = "rt/tf";
  /// Output: the global map as sensor_msgs/PointCloud2 in frame "map" (map_cloud.hpp: x, y, z
  /// of every fused distribution's mean and its point count), sent whole when tiles changed,
  /// at most every publish.tiles_period_s; transient-local, so a late viewer gets the latest.
  /// Empty (the default): none.
  std::string map_cloud;
};

struct StoreConfig {
  /// The SQLite store (created if missing; a file that is not a keyframe store is refused).
  std::string path = "/var/lib/litamin2/aggregator.db";
  /// fsync at every commit (survives power loss; kill -9 is survived either way).
  bool synchronous_full = false;
  /// Megabytes of keyframe distributions kept in memory (the mapper's DistributionCache); the
  /// rest is read back from the store when a verification or the map needs it.
  int distribution_cache_mb = 512;
  /// Connections reading the graph's rows side by side at a restart (StoreOptions).
  int restart_readers = 4;
  /// KiB of an SQLite page when the store is created (1 to 64, a power of two; StoreOptions).
  int page_size_kb = 64;
  /// MiB of SQLite's page cache per connection (StoreOptions).
  int sqlite_cache_mb = 64;
};

struct IngestConfig {
  /// Patches queued between the DDS listener and the mapping thread; when full the listener
  /// waits (reliable DDS then holds the writers back) instead of dropping.
  int queue_capacity = 1024;
  /// At most this many patches are committed to the store in one transaction.
  int max_batch = 256;
  /// Read the streams' odometry (topics.odometry) with EXCLUSIVE ownership: needed when the
  /// daemons run hot standby (litamin2d sharding.replicas > 1), whose odometry writers are
  /// exclusive (a SHARED reader would not match them), and wrong otherwise (it would match no
  /// shared writer).
  bool exclusive_odometry = false;
};

struct PublishConfig {
  /// Corrected poses of keyframes that were added or moved are published at most this often,
  /// seconds, in chunks of ...
  double poses_period_s = 1.0;
  /// ... this many consecutive keyframe ids of a stream: a publication sends again only the
  /// chunks holding a keyframe that changed (KeyframePoses is keyed by stream and chunk, so a
  /// late joiner still gets every chunk). 0: one chunk per stream (every keyframe of it, sent
  /// whole whenever one of them moves: at 10^6 keyframes, 10^4 a stream, that cost 1.8 ms of
  /// the mapping thread a keyframe, docs/benchmarks.md "10^6 keyframes").
  int poses_chunk_keyframes = 256;
  /// The map summary (made from the tile index) is published at most this often (when
  /// changed), seconds.
  double summary_period_s = 10.0;
  /// Voxel means listed in the summary at most (decimated evenly from the tiles' samples of
  /// 32 means each); 0 = counts only.
  int summary_max_means = 10000;
  /// The mapping thread hands the map tiles that changed over (to topics.map_tiles, which
  /// also spaces each tile by map_tiles.publish_period_s, and to topics.map_cloud) at most
  /// this often, seconds.
  double tiles_period_s = 2.0;
  /// Status period, seconds.
  double status_period_s = 1.0;
  /// Poses on rt/<stream>/map_odom and map -> odom transforms in the map frame start this
  /// long after the first keyframe, seconds (held until then, the latest kept): vehicles that
  /// start together send their first patches in any order, and the map frame (the odometry
  /// frame of the stream that starts first) is settled only once all of them arrived.
  double map_frame_settle_s = 2.0;
};

/// The global map in tiles (mapping/tile_map.hpp).
struct MapTilesConfig {
  mapping::TileMapConfig tiles;
  /// Keyframes fused into (or moved in) the tiles per turn of the mapping thread at most: a
  /// full pass that moves most of the map is folded into the tiles over many turns.
  int max_keyframes_per_turn = 400;
  /// Megabytes of tiles held in memory; the others are read back from the store.
  int cache_mb = 256;
  /// A tile goes out on topics.map_tiles at most once per this many seconds: its changes
  /// within the period go out together, once, with the newest revision (0: each change at
  /// once; at most 3600).
  double publish_period_s = 1.0;
  /// The changed tiles and the poses their keyframes are fused at are stored at most once per
  /// this many seconds (and at stop), in one transaction; in between they wait in memory, so
  /// a tile changed in many turns is written once. A restart (kill -9 too) fuses again what
  /// was fused after the last store (0: every turn; at most 3600).
  double persist_period_s = 5.0;
};

/// Bounds on what a client may send (docs/security.md, "Validation").
struct LimitsConfig {
  /// A map patch with more distributions is rejected (too_many_distributions) before any is
  /// converted; its serialised payload may be at most 40 bytes a distribution plus 1 MiB.
  int max_distributions_per_patch = 200'000;
  /// The map patch reader's samples have fixed buffers of that payload limit (Fast DDS's
  /// PREALLOCATED history memory): a sample announced larger is dropped by Fast DDS before it
  /// allocates or reassembles anything (without: a writer announcing a 2 GB fragmented sample
  /// makes the reader allocate 2 GB before any check). Costs the whole limit per sample held
  /// (9.0 MB with the default max_distributions_per_patch, whatever the patch's size), so
  /// lower max_distributions_per_patch with it. Off by default. docs/security.md.
  bool fixed_patch_payloads = false;
};

/// Hot standby of the aggregator itself: two aggregators on the same (durable) map patches, each
/// with its own store, publish the same outputs; with a strength > 0 their output writers are
/// EXCLUSIVE, so an exclusive reader takes the strongest live aggregator's samples only and
/// switches to the next one when that one's participant is dropped (its lease).
struct StandbyConfig {
  /// Ownership strength of the output writers (keyframe poses, map summary, map tiles, map
  /// cloud, map-frame odometry). 0: SHARED ownership, as without standby (every reader gets
  /// every aggregator's samples). > 0: EXCLUSIVE at this strength; give each aggregator a
  /// different one (the highest is the owner). Status, diagnostics and rt/tf stay SHARED (see
  /// docs/deploy.md, "Hot standby").
  int strength = 0;
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
  MapTilesConfig map_tiles;
  /// The background full pass of the pose graph (full_pass_worker.hpp).
  FullPassConfig full_pass;
  StandbyConfig standby;
  /// A batch may take longer than a frame: 60 s stall timeout (the shipped file's), not 10.
  service::WatchdogConfig watchdog{true, 60.0};
  /// The Prometheus endpoint (off unless metrics.listen is set).
  service::MetricsConfig metrics;
  /// spdlog level: trace, debug, info, warn, error, critical, off.
  std::string log_level = "info";
};

/// Throws ConfigError naming the key (as a dotted path) on the first invalid value: topics that
/// are not valid topic names or not distinct, odometry patterns without exactly one '*', an
/// empty store path, an unknown log level, an invalid mapper section.
void validate(const AggregatorConfig& config);

}  // namespace litamin2::aggregator
