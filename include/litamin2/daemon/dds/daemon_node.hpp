#pragma once
/// The daemon's DDS side: one participant; per stream a reader of rt/<stream>/points (created
/// when discovery reports a writer, reliable if the writer is; a stream of several sensors has
/// one reader per topic, their scans merged by MergedInput), a tracker on the shared
/// StreamScheduler, a writer of rt/<stream>/odom and a writer of the map patches in the
/// partition of the stream id (dds/stream_partition.hpp); one writer each for status (also on
/// rt/diagnostics unless outputs.diagnostics_topic is empty), rt/tf (every stream's odom -> base
/// per pose) and rt/tf_static (every stream's base -> sensor, transient-local). Streams come from
/// the config and, with discovery enabled, from every PointCloud2 topic matching the pattern. The
/// main loop calls poll(); shutdown() stops input, drains the queues within the configured time and
/// publishes a final status. With sharding (docs/deploy.md, "Several daemon hosts") the participant
/// announces the member id in its USER_DATA, the node follows the live daemons (Membership) and
/// tracks only the discovered streams that rendezvous hashing gives it; it reads every known
/// stream's rt/<stream>/odom and the map patches' keyframe ids (HandoverListener, every partition)
/// so that a stream moving here continues its odometry frame and keyframe ids
/// (stream_handover.hpp).

#include "litamin2/daemon/daemon_config.hpp"
#include "litamin2/daemon/dds/handover_listener.hpp"
#include "litamin2/daemon/dds/publisher_discovery.hpp"
#include "litamin2/daemon/dds/status_message.hpp"
#include "litamin2/daemon/membership.hpp"
#include "litamin2/daemon/stream_scheduler.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/service/topic_names.hpp"

#include <fastdds/dds/topic/TypeSupport.hpp>

#include "tf2_msgs/msg/TFMessage.h"

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace eprosima::fastdds::dds {
class Publisher;
class Subscriber;
class Topic;
class DataWriter;
}  // namespace eprosima::fastdds::dds

namespace litamin2::daemon {

class DaemonNode {
 public:
  using Clock = std::chrono::steady_clock;

  /// Creates the participant, the output writers, the scheduler and the configured streams'
  /// trackers. Throws std::runtime_error if DDS refuses (bad XML profile, ...) and ConfigError
  /// for an invalid tracker config.
  explicit DaemonNode(DaemonConfig config);
  /// Shuts down (if not done) and deletes every DDS entity.
  ~DaemonNode();
  DaemonNode(const DaemonNode&) = delete;
  DaemonNode& operator=(const DaemonNode&) = delete;

  /// Main-loop work: readers (and trackers) for newly discovered writers, status when due.
  void poll(Clock::time_point now = Clock::now());
  /// No frame has been in processing for longer than the watchdog's stall timeout.
  bool healthy(Clock::time_point now = Clock::now()) const;
  /// Stops reading, gives queued frames up to shutdown_timeout_s, publishes the last status.
  /// Idempotent.
  DrainResult shutdown();

  /// Streams with a tracker here (sharding: also those that moved away since).
  std::size_t stream_count() const { return streams_.size(); }
  /// Sharding: the live members (empty without sharding).
  std::vector<std::string> members() const;
  /// Sharding: streams started here from another daemon's last pose.
  std::uint64_t takeovers() const { return takeovers_; }
  /// Every stream's statistics and counters (levels and messages as in the last status).
  std::vector<StreamStatus> status(Clock::time_point now = Clock::now()) const;
  /// One line for logs and sd_notify STATUS=.
  std::string summary(Clock::time_point now = Clock::now()) const;
  /// The Prometheus /metrics text of status(now) (daemon_metrics.hpp).
  std::string metrics_text(Clock::time_point now = Clock::now()) const;

 private:
  struct Input;
  struct Stream;

  Stream& add_stream(StreamConfig config, std::optional<HandoverSeed> seed = std::nullopt);
  /// The participant's topic `name`, created (of `type`) if it does not exist yet.
  eprosima::fastdds::dds::Topic* topic(const std::string& name, const std::string& type);
  void start_processor(Stream& stream, std::optional<HandoverSeed> seed);
  Stream* find_by_id(const std::string& id);
  void on_sharded_writer(const DiscoveredWriter& writer);
  void reshard(Clock::time_point now);
  /// Hot standby (sharding.replicas > 1): this daemon's place `rank` for the stream sets its
  /// odometry writer's ownership strength (replicas - rank); a standby (rank > 0) holds its
  /// map patches, the owner (rank 0) writes them, and on promotion the held ones the old
  /// owner did not publish.
  void set_role(Stream& stream, std::size_t rank);
  std::optional<HandoverSeed> handover_seed(const std::string& id) const;
  /// The stream reading `topic` (its only topic or one of its sensors'), and that input.
  std::pair<Stream*, Input*> find_by_topic(const std::string& topic);
  /// Some input of the stream has a reader.
  static bool reading(const Stream& stream);
  /// The stream's input topics, comma-separated.
  static std::string input_topics(const Stream& stream);
  void on_writer(const DiscoveredWriter& writer);
  void attach_reader(Stream& stream, Input& input, bool reliable);
  /// The stream's zero-copy reader of config.zero_copy_topic (PlainScan, data-sharing, loans).
  void attach_zero_copy_reader(Stream& stream, const dds::CloudConversionOptions& conversion);
  void detach_reader(Input& input);
  /// Every input's reader.
  void detach_reader(Stream& stream);
  void publish_status(Clock::time_point now);

  DaemonConfig config_;
  std::optional<service::TopicPattern> pattern_;
  std::unique_ptr<PublisherDiscovery> discovery_;
  dds::ParticipantPtr participant_;
  eprosima::fastdds::dds::TypeSupport points_type_;
  /// Registered with the first stream that has a zero_copy_topic.
  eprosima::fastdds::dds::TypeSupport plain_scan_type_;
  eprosima::fastdds::dds::TypeSupport odom_type_;
  eprosima::fastdds::dds::TypeSupport map_patch_type_;
  eprosima::fastdds::dds::TypeSupport status_type_;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  /// Map patches: each stream has its publisher (partition = stream id) and writer.
  eprosima::fastdds::dds::Topic* patches_topic_ = nullptr;
  eprosima::fastdds::dds::DataWriter* status_writer_ = nullptr;
  /// outputs.diagnostics_topic (null when empty): the status again, for ROS 2's /diagnostics.
  eprosima::fastdds::dds::DataWriter* diagnostics_writer_ = nullptr;
  /// rt/tf and rt/tf_static (outputs.publish_tf; null without).
  eprosima::fastdds::dds::TypeSupport tf_type_;
  eprosima::fastdds::dds::DataWriter* tf_writer_ = nullptr;
  eprosima::fastdds::dds::DataWriter* tf_static_writer_ = nullptr;
  /// Every stream's base -> sensor, as last written on rt/tf_static.
  tf2_msgs::msg::TFMessage static_transforms_;
  std::unique_ptr<StreamScheduler> scheduler_;
  std::vector<std::unique_ptr<Stream>> streams_;
  /// Sharding: every discovered stream, tracked here or not.
  struct KnownStream {
    std::string topic;
    bool reliable = true;
    eprosima::fastdds::dds::DataReader* odom_reader = nullptr;
  };
  std::optional<Membership> membership_;
  std::map<std::string, KnownStream> known_;
  HandoverListener handover_;
  eprosima::fastdds::dds::DataReader* patch_ids_reader_ = nullptr;
  /// patch_ids_reader_'s subscriber: every partition (one per stream, dds/stream_partition.hpp).
  eprosima::fastdds::dds::Subscriber* patch_ids_subscriber_ = nullptr;
  std::string own_participant_;
  Clock::time_point claim_after_{};
  bool claiming_ = false;
  std::uint64_t takeovers_ = 0;
  std::uint64_t reported_rejected_members_ = 0;
  Clock::time_point next_status_{};
  bool stopped_ = false;
};

}  // namespace litamin2::daemon
