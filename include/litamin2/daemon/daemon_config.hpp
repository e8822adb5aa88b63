#pragma once
/// The daemon's configuration (litamin2d.yaml): DDS participant, sensor streams, topic
/// discovery, threads, queues, outputs, watchdog and logging, and its validation (read from
/// YAML by config/daemon_config_yaml.hpp).

#include "litamin2/core/tracker_config.hpp"
#include "litamin2/daemon/scan_merger.hpp"
#include "litamin2/daemon/worker_scheduling.hpp"
#include "litamin2/service/metrics_config.hpp"
#include "litamin2/service/security_config.hpp"
#include "litamin2/service/transport_config.hpp"
#include "litamin2/service/watchdog_config.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::daemon {

/// One of several sensors merged into a stream (scan_merger.hpp).
struct SensorInput {
  /// Input topic of sensor_msgs/PointCloud2.
  std::string topic;
  /// The sensor's pose in the vehicle (base) frame: its points are moved into the base by it.
  Eigen::Isometry3d extrinsic = Eigen::Isometry3d::Identity();
};

/// One sensor stream: its input topic (or several sensors' topics), the sensor's mounting and
/// its tracker.
struct StreamConfig {
  /// Unique id; output topics are named after it (rt/<id>/odom).
  std::string id;
  /// Input topic of sensor_msgs/PointCloud2 (default rt/<id>/points); empty when `inputs` is
  /// given.
  std::string topic;
  /// Sensor pose in the vehicle (base) frame; the published odometry is the base's pose.
  /// Identity when `inputs` is given (the merged scans are in the base frame already).
  Eigen::Isometry3d extrinsic = Eigen::Isometry3d::Identity();
  /// Opt-in same-host zero-copy input (YAML zero_copy_topic; empty: none, the default): a
  /// second reader of the stream, of litamin2_zero_copy/PlainScan (a fixed-size type, not a ROS 2
  /// one) with data-sharing and loans, for a driver on this host (docs/ros2.md, "Zero-copy input").
  /// Its scans go through the same checks and stamp order as the PointCloud2 topic's. Only for
  /// a stream of one `topic`.
  std::string zero_copy_topic;
  /// Several sensors of the vehicle (YAML `topics:`): their scans, each moved to the base
  /// frame by its extrinsic, merged by stamp into one frame per sweep for the one tracker.
  /// Empty: the single `topic`.
  std::vector<SensorInput> inputs;
  /// How `inputs` are merged (YAML merge_window_s, merge_timeout_s); unused without them.
  ScanMergerConfig merge;
  /// The global tracker section with this stream's overrides merged over it.
  TrackerConfig tracker;
  /// The sensor's frame, used verbatim (e.g. the frame_id the driver puts in its PointCloud2
  /// headers, so that rviz2 places the scans); empty: outputs.sensor_frame with the stream rule.
  std::string sensor_frame;
};

/// The daemon's tracker defaults: TrackerConfig's, with deskew on (live drivers publish per-point
/// times; a scan without them is registered as it is and counted), as in the shipped
/// litamin2d.yaml.
TrackerConfig daemon_tracker_defaults();

/// Streams started for every input topic that DDS discovery reports and that matches.
struct DiscoveryConfig {
  /// On by default, as in the shipped litamin2d.yaml: a config that gives only `dds:` runs.
  bool enabled = true;
  /// Glob over topic names with exactly one '*', which becomes the stream id
  /// ("rt/*/points": topic rt/car1/points -> stream car1).
  std::string pattern = "rt/*/points";
  /// Upper bound on the number of discovered streams (memory and threads stay bounded).
  int max_streams = 64;
};

struct OutputsConfig {
  /// Odometry goes to rt/<stream>/<odom_suffix>.
  std::string odom_suffix = "odom";
  std::string map_patches_topic = "rt/litamin2/map_patches";
  std::string status_topic = "rt/litamin2/status";
  /// The same status also here: ROS 2's /diagnostics (rqt_robot_monitor, diagnostic_aggregator
  /// read it), with diagnostic_updater's QoS. Empty: only on status_topic.
  std::string diagnostics_topic = "rt/diagnostics";
  /// Status (DiagnosticArray) period, seconds.
  double status_period_s = 1.0;
  /// Map patches held per stream for aggregators that start late or restart (transient-local):
  /// about 40 KB each at 3 m voxels, so 500 are ~20 MB per stream and, at a keyframe every
  /// 2 m and 10 m/s, the last 100 s of driving.
  int map_patch_history = 500;
  /// Frame names (REP-105 defaults). A stream's frames are "<stream>/<name>" with
  /// frame_prefix (stream_frames.hpp): its odometry header and rt/tf parent "<stream>/odom",
  /// the child "<stream>/base_link", the sensor (rt/tf_static child of base_link, the
  /// extrinsic) "<stream>/lidar" unless the stream names its own sensor_frame.
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  std::string sensor_frame = "lidar";
  /// false: the names as given, without the stream prefix (one configured stream only, no
  /// discovery: two streams' frames would collide).
  bool frame_prefix = true;
  /// Publish tf2_msgs/TFMessage: odom -> base per pose on tf_topic, base -> sensor (static) on
  /// tf_static_topic (transient-local, as ROS 2's static broadcaster).
  bool publish_tf = true;
  std::string tf_topic = "rt/tf";
  std::string tf_static_topic = "rt/tf_static";
};

/// Streams spread over several live daemons (docs/deploy.md, "Several daemon hosts"): each
/// discovered stream is tracked by one daemon, chosen by rendezvous hashing over the members
/// that DDS discovery reports alive (membership.hpp, rendezvous.hpp).
struct ShardingConfig {
  bool enabled = false;
  /// Seconds after start before this daemon claims streams, so that it has discovered the
  /// other daemons first (otherwise it would track every stream until they appear). At least
  /// the time discovery takes: about one lease announcement period.
  double startup_wait_s = 3.0;
  /// A stream that moves here starts from its last odometry pose moved on at its last twist to
  /// the first scan here (constant velocity), when the gap is at most this many seconds;
  /// beyond, from the last pose as it is.
  double max_extrapolation_s = 10.0;
  /// A stream that moves here continues against the map of its last this many map patches
  /// (stream_handover.hpp) instead of starting a new map at the extrapolated pose; 0: never.
  /// Every sharded daemon keeps up to this many patches of each known stream (memory: this
  /// times a patch's size, ~40 bytes a distribution, per stream).
  int seed_keyframes = 10;
  /// Patches whose stamp is more than this many seconds before the stream's last odometry are
  /// not used (a stream that stood still or lost its keyframes for longer starts a new map).
  double seed_max_age_s = 10.0;
  /// Hot standby (docs/deploy.md, "Hot standby"): each stream is tracked by the first
  /// `replicas` live members in its rendezvous order (1: by its owner only). With more than
  /// one, the odometry writers use EXCLUSIVE ownership at strength `replicas - rank` (the
  /// owner's is the highest), so exclusive readers get one stream of odometry and move to the
  /// standby when the owner's participant lease expires; a standby holds its map patches
  /// (up to outputs.map_patch_history) and publishes those after the owner's last when it
  /// becomes the owner. Readers of rt/<stream>/odom must then be exclusive (a SHARED reader,
  /// e.g. a ROS 2 node, does not match).
  int replicas = 1;
};

/// Bounds on what a client may send (docs/security.md, "Validation").
struct LimitsConfig {
  /// A PointCloud2 with more points (width * height) is rejected (too_many_points) before any
  /// point is read.
  int max_points_per_scan = 5'000'000;
};

/// The largest memory.prefault_mb accepted (64 GiB).
inline constexpr int kMaxPrefaultMiB = 65536;

/// The heap touched before the first scan (service::prefault_heap; docs/deploy.md, "Memory").
struct MemoryConfig {
  /// MiB of heap touched at start and kept: Fast DDS's sample buffers, the converted clouds and
  /// the trackers' maps then come from pages already in place, instead of being faulted in while
  /// the first scans arrive. 0: off. Absent or "auto": prefault_auto_mb().
  std::optional<int> prefault_mb;
};

struct DaemonConfig {
  service::TransportConfig dds;
  /// DDS-Security (off by default).
  service::SecurityConfig security;
  LimitsConfig limits;
  /// Statically configured streams.
  std::vector<StreamConfig> streams;
  DiscoveryConfig discovery;
  /// This daemon's name among the daemons of the domain (membership.hpp's member_id_error);
  /// empty: the host name.
  std::string member_id;
  ShardingConfig sharding;
  /// The global tracker section (streams and discovered streams start from it); absent keys
  /// from daemon_tracker_defaults().
  TrackerConfig tracker = daemon_tracker_defaults();
  /// Worker threads of the stream scheduler (StreamScheduler); 0 = one per core.
  int threads = 0;
  /// The workers' scheduling class and CPUs (YAML scheduling: {policy, priority, cpus});
  /// default: SCHED_OTHER, CPUs inherited, as any thread.
  WorkerScheduling scheduling;
  /// Frames queued per stream before the oldest is dropped.
  int queue_depth = 4;
  MemoryConfig memory;
  OutputsConfig outputs;
  service::WatchdogConfig watchdog;
  /// The Prometheus endpoint (off unless metrics.listen is set).
  service::MetricsConfig metrics;
  /// spdlog level: trace, debug, info, warn, error, critical, off.
  std::string log_level = "info";
  /// Seconds given at shutdown to the queued frames (dropped after it) and then, with what is
  /// left, to the readers' acknowledgment of the map patches written.
  double shutdown_timeout_s = 1.0;
};

/// "auto": 64 MiB and 32 MiB a configured stream (at least one; a daemon that discovers its
/// streams counts one), at most 1024 MiB. Measured (docs/benchmarks.md, "The heap touched before
/// the first scan"): ~20 MiB an HDL-64-size stream, ~7 MiB a VLP-16-size one.
int prefault_auto_mb(const DaemonConfig& config);

/// The bytes the daemon touches at start: memory.prefault_mb, or prefault_auto_mb().
std::size_t prefault_bytes(const DaemonConfig& config);

/// Throws ConfigError naming the key (as a dotted path) on the first invalid value: stream ids
/// that are not valid (service::stream_id_error) or duplicate, topics that are not valid topic
/// names or used twice (by any stream or input), a stream with both `topic` and `inputs`, or
/// with `inputs` and an extrinsic of its own, an input's extrinsic that is not rigid, an invalid
/// merge config, a discovery pattern without exactly one '*', an empty odometry frame,
/// an unknown log level, neither streams nor discovery, and invalid tracker sections; frame
/// names that are empty, start with '/' or hold whitespace (tf2 refuses them), equal odom and
/// base frames, and frame_prefix false with more than one stream or with discovery; an invalid
/// member_id; an invalid scheduling section (worker_scheduling_error); sharding without
/// discovery or with configured streams (every daemon would track
/// them), and negative sharding times.
void validate(const DaemonConfig& config);

/// config.member_id, or the host name when it is empty. Throws ConfigError (key member_id) when
/// the result is not a member id.
std::string resolved_member_id(const DaemonConfig& config);

/// A stream for a discovered topic: id from the pattern, the global tracker, no extrinsic.
StreamConfig discovered_stream(const DaemonConfig& config, const std::string& id,
                               const std::string& topic);

}  // namespace litamin2::daemon
