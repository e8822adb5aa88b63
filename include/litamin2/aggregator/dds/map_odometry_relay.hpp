#pragma once
/// Publishes each stream's current pose in the map frame (map_odometry.hpp) from its odometry.
///
/// The odometry listeners only offer() the converted message (a short lock, the latest message
/// of a stream replacing one not yet published); the mapping thread updates each stream's
/// correction when it publishes the stream's corrected poses; a thread of the relay composes and
/// publishes (the map transform also when only the correction changed). A stream without a
/// correction yet (odometry before its first keyframe reached the mapper) gets nothing published.
/// Counters per stream for the status.

#include "litamin2/aggregator/dds/map_odometry.hpp"
#include "nav_msgs/msg/Odometry.h"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace litamin2::aggregator {

/// One stream's odometry as the status reports it.
struct OdometryStreamStatus {
  std::uint64_t received = 0;
  /// Messages with a non-finite pose, dropped.
  std::uint64_t rejected = 0;
  /// Map-frame poses published.
  std::uint64_t published = 0;
  /// Received before the stream had a keyframe in the mapper: nothing published for them.
  std::uint64_t before_keyframe = 0;
  /// Odometry messages per second over the last completed window of at least 1 s (0 when
  /// none arrived for longer than that).
  double rate_hz = 0.0;
  /// Seconds since the last message; negative when none arrived yet.
  double last_seen_s = -1.0;
  /// The frame the stream's map-frame poses are in ("" before its first keyframe).
  std::string frame_id;
};

class MapOdometryRelay {
 public:
  using Clock = std::chrono::steady_clock;
  /// Writes one map-frame odometry message of a stream; called on the relay's thread.
  using Publish = std::function<void(const nav_msgs::msg::Odometry&)>;
  /// Writes the stream's map -> odom transform (to_map_transform) with each of those poses.
  using PublishTransform = std::function<void(const geometry_msgs::msg::TransformStamped&)>;

  /// `map_frame_settle`: poses and transforms in the map frame go out only once this long has
  /// passed since the first correction (held, the latest kept, until then; other frames are not
  /// held). When several vehicles start together, the map frame belongs to the stream that
  /// starts first, but their first patches reach the aggregator in any order, and for a moment
  /// the map frame may be another vehicle's odometry frame; poses published in it then would
  /// be wrong by the distance between the vehicles.
  explicit MapOdometryRelay(std::chrono::milliseconds map_frame_settle = {});
  /// Stops (see stop()).
  ~MapOdometryRelay();
  MapOdometryRelay(const MapOdometryRelay&) = delete;
  MapOdometryRelay& operator=(const MapOdometryRelay&) = delete;

  /// Registers a stream and where its map-frame poses (and, if given, its map -> odom
  /// transforms) go, before its odometry is read.
  void add_stream(const std::string& stream, Publish publish,
                  PublishTransform publish_transform = {});
  /// Listener thread: the stream's latest odometry. Never waits but for a short lock.
  void offer(const std::string& stream, nav_msgs::msg::Odometry odom,
             Clock::time_point now = Clock::now());
  /// Listener thread: a message that could not be used.
  void reject(const std::string& stream);
  /// Mapping thread: the stream's correction changed. When it differs from the last one and the
  /// stream has a transform publisher, the map transform goes out at once (stamped with the
  /// latest odometry, unless a transform went out at that stamp already), not only with the
  /// next pose.
  void set_correction(const std::string& stream, MapCorrection correction);

  /// Starts the publishing thread.
  void start();
  /// Publishes what is pending, then joins. Idempotent; later offers are counted only.
  void stop();
  /// Composes and publishes what is pending on the calling thread (tests; start() does this).
  void flush();

  std::map<std::string, OdometryStreamStatus> status(Clock::time_point now = Clock::now()) const;

 private:
  struct Stream {
    Publish publish;
    PublishTransform publish_transform;
    /// The latest odometry's header (stamp, frame), and a map transform to send for it (the
    /// correction changed since the last pose).
    std::optional<std_msgs::msg::Header> last_header;
    bool transform_pending = false;
    /// Stamp of the last map transform sent (one per stamp: tf2 ignores repeated stamps).
    builtin_interfaces::msg::Time transform_stamp;
    std::optional<nav_msgs::msg::Odometry> pending;
    std::optional<MapCorrection> correction;
    OdometryStreamStatus counts;
    Clock::time_point last_seen{};
    Clock::time_point window_start{};
    std::uint64_t window_count = 0;
  };
  void run();
  /// Map-frame outputs are still held (see the constructor); caller holds mutex_.
  bool settling(Clock::time_point now) const;

  const std::chrono::milliseconds map_frame_settle_;
  /// The first correction's time plus map_frame_settle_.
  std::optional<Clock::time_point> settle_end_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, Stream> streams_;
  bool pending_ = false;
  /// Map-frame outputs were held back by the settling.
  bool held_ = false;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace litamin2::aggregator
