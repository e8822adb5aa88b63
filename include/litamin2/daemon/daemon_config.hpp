#pragma once
/// The daemon's configuration (litamin2d.yaml): DDS participant, sensor streams, topic
/// discovery, threads, queues, outputs, watchdog and logging, with YAML load and validation.

#include "litamin2/core/tracker_config.hpp"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace litamin2::daemon {

/// How the DDS participant's transports are set up.
enum class TransportProfile {
  /// UDPv4 restricted to 127.0.0.1, unicast discovery, plus a large shared-memory segment:
  /// nothing leaves the machine.
  loopback,
  /// Shared memory with a large segment (plus UDP for discovery), for large local scans.
  shm,
  /// Fast DDS's built-in transports and multicast discovery.
  default_profile,
  /// A participant profile from a Fast DDS XML file.
  xml,
};

/// The name used in the YAML file ("loopback", "shm", "default", "xml").
const char* to_string(TransportProfile profile);

struct DdsConfig {
  /// DDS domain id (0..232).
  int domain = 0;
  TransportProfile profile = TransportProfile::loopback;
  /// For TransportProfile::xml: the XML file and the participant profile name in it.
  std::string xml_file;
  std::string xml_profile;
};

/// Reads a `dds:` section (a null node gives the defaults), shared by the daemon's and the
/// aggregator's configs; errors name keys as dds.<key>.
DdsConfig dds_config_from_yaml(const YAML::Node& node);

/// One sensor stream: its input topic, the sensor's mounting and its tracker.
struct StreamConfig {
  /// Unique id; output topics are named after it (rt/<id>/odom).
  std::string id;
  /// Input topic of sensor_msgs/PointCloud2 (default rt/<id>/points).
  std::string topic;
  /// Sensor pose in the vehicle (base) frame; the published odometry is the base's pose.
  Eigen::Isometry3d extrinsic = Eigen::Isometry3d::Identity();
  /// The global tracker section with this stream's overrides merged over it.
  TrackerConfig tracker;
};

/// Streams started for every input topic that DDS discovery reports and that matches.
struct DiscoveryConfig {
  bool enabled = false;
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
  /// Status (DiagnosticArray) period, seconds.
  double status_period_s = 1.0;
  /// Map patches held per stream for aggregators that start late or restart (transient-local):
  /// about 40 KB each at 3 m voxels, so 500 are ~20 MB per stream and, at a keyframe every
  /// 2 m and 10 m/s, the last 100 s of driving.
  int map_patch_history = 500;
  /// frame_id of published odometry headers; child_frame_id is "<stream>/base_link".
  std::string odom_frame = "odom";
};

/// The systemd watchdog: WATCHDOG=1 is sent (at half of $WATCHDOG_USEC) only while no frame
/// has been in processing for longer than stall_timeout_s, so a wedged daemon is restarted.
struct WatchdogConfig {
  bool enabled = true;
  double stall_timeout_s = 10.0;
};

struct DaemonConfig {
  DdsConfig dds;
  /// Statically configured streams.
  std::vector<StreamConfig> streams;
  DiscoveryConfig discovery;
  /// The global tracker section (streams and discovered streams start from it).
  TrackerConfig tracker;
  /// Worker threads of the processing arena; 0 = one per core.
  int threads = 0;
  /// Frames queued per stream before the oldest is dropped.
  int queue_depth = 4;
  OutputsConfig outputs;
  WatchdogConfig watchdog;
  /// spdlog level: trace, debug, info, warn, error, critical, off.
  std::string log_level = "info";
  /// Seconds given to queued frames at shutdown before they are dropped.
  double shutdown_timeout_s = 1.0;
};

/// Reads a daemon config from a YAML mapping. Absent keys keep their defaults; unknown keys,
/// values of the wrong type or out of range, duplicate stream ids or topics, and configs with
/// neither streams nor discovery throw ConfigError naming the key and the value.
DaemonConfig daemon_config_from_yaml(const YAML::Node& node);
/// Reads a YAML file; error messages start with the file name.
DaemonConfig load_daemon_config(const std::string& path);

/// The stream id a discovered topic gets from the glob `pattern`, or nothing if it does not
/// match (or the id would be empty or contain characters not allowed in a stream id).
std::optional<std::string> match_topic_pattern(const std::string& pattern,
                                               const std::string& topic);
/// Stream ids are ROS 2 relative namespaces: tokens of letters, digits and '_' (not starting
/// with a digit, no "__") separated by single '/'.
bool is_valid_stream_id(const std::string& id);

/// A stream for a discovered topic: id from the pattern, the global tracker, no extrinsic.
StreamConfig discovered_stream(const DaemonConfig& config, const std::string& id,
                               const std::string& topic);

}  // namespace litamin2::daemon
