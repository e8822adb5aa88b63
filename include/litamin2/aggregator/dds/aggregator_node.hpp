#pragma once
/// The aggregator's DDS side: one participant; a reader of the map patches (reliable,
/// transient-local, keep-all, every partition) whose listener only checks that each patch's
/// stream is a partition of its writer (dds/stream_partition.hpp), converts and enqueues; writers
/// of the corrected keyframe poses (one instance per stream, reliable, transient-local), of the map
/// summary (reliable, transient-local), of the map tiles (one instance per tile, reliable,
/// transient-local, each tile at most once per map_tiles.publish_period_s: map_tile_publisher.hpp)
/// and of the status (DiagnosticArray, also on
/// topics.diagnostics: rt/diagnostics); the mapping thread
/// in between. For every stream seen in the patches (or recovered from the store), a reader of
/// its odometry (reliable, keep-last, as litamin2d writes it) and a writer of its current pose
/// in the map frame (map_odometry.hpp), created by the main loop; a MapOdometryRelay between
/// them. With standby.strength > 0 the map outputs (poses, summary, tiles, cloud, map-frame
/// odometry) are EXCLUSIVE at that strength: the hot standby of two aggregators on the same
/// patches (docs/deploy.md, "Hot standby"). The store is opened (and the mapper rebuilt from it)
/// before DDS starts, so a store that cannot be opened fails the start with nothing published.

#include "litamin2/aggregator/aggregator_config.hpp"
#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/dds/aggregator_messages.hpp"
#include "litamin2/aggregator/dds/map_odometry_relay.hpp"
#include "litamin2/aggregator/dds/map_tile_publisher.hpp"
#include "litamin2/aggregator/dds/odometry_listener.hpp"
#include "litamin2/aggregator/dds/patch_listener.hpp"
#include "litamin2/aggregator/map_cloud.hpp"
#include "litamin2/aggregator/mapping_worker.hpp"
#include "litamin2/aggregator/patch_queue.hpp"
#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/writer_partitions.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"

#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace eprosima::fastdds::dds {
class Publisher;
class Subscriber;
class DataReader;
class DataWriter;
}  // namespace eprosima::fastdds::dds

namespace litamin2::aggregator {

class AggregatorNode {
 public:
  using Clock = std::chrono::steady_clock;

  /// Opens the store (StoreError), rebuilds the mapper (`progress` reports it), creates the DDS
  /// entities (std::runtime_error if DDS refuses), publishes the recovered poses and starts
  /// reading patches.
  AggregatorNode(AggregatorConfig config, const AggregatorCore::Progress& progress = {});
  ~AggregatorNode();
  AggregatorNode(const AggregatorNode&) = delete;
  AggregatorNode& operator=(const AggregatorNode&) = delete;

  /// Main-loop work: odometry readers for new streams, the status when due.
  void poll(Clock::time_point now = Clock::now());
  /// The mapping thread is not stalled and the store works.
  bool healthy(Clock::time_point now = Clock::now()) const;
  /// The store failed: exit (non-zero) so that the service is restarted.
  bool failed() const;
  /// Stops reading, commits and maps what is queued, publishes the last outputs. Idempotent.
  void shutdown();

  WorkerStatus status() const;
  /// One line for logs and sd_notify STATUS=.
  std::string summary() const;
  /// The Prometheus /metrics text of the status (aggregator_metrics.hpp).
  std::string metrics_text() const;

 private:
  class Sink;
  /// The map's points: written by the mapping thread (Sink::publish_tile), read by poll().
  struct MapCloudBuffer {
    std::mutex mutex;
    MapCloud cloud;
    bool changed = false;
  };
  /// An output writer's QoS with the hot standby's ownership (standby.strength; SHARED at 0).
  eprosima::fastdds::dds::DataWriterQos output_qos(eprosima::fastdds::dds::DataWriterQos qos) const;
  void publish_status(Clock::time_point now);
  /// The listener's and the queue's counters, as the status reports them.
  IngestCounters ingest_counters() const;
  /// Sends the map's points if tiles changed since the last time.
  void publish_map_cloud(Clock::time_point now);
  /// Odometry reader and map-frame writer for streams that have none yet.
  void subscribe_odometry(const WorkerStatus& status);

  struct OdometryStream {
    std::unique_ptr<OdometryListener> listener;
    eprosima::fastdds::dds::DataReader* reader = nullptr;
  };

  AggregatorConfig config_;
  std::unique_ptr<AggregatorCore> core_;
  PatchQueue queue_;
  /// The map patch writers' partitions (the participant's listener): outlives the participant.
  dds::WriterPartitions writer_partitions_;
  PatchListener listener_;
  dds::ParticipantPtr participant_;
  eprosima::fastdds::dds::TypeSupport patch_type_, poses_type_, summary_type_, status_type_,
      odometry_type_, tf_type_, cloud_type_, tile_type_;
  /// The types of patch_type_ and odometry_type_ (owned by them), for their failure counts.
  dds::CheckedType<litamin2::msg::MapPatchPubSubType>* checked_patch_type_ = nullptr;
  dds::CheckedType<nav_msgs::msg::OdometryPubSubType>* checked_odometry_type_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  /// The map patches' subscriber: every partition (one per stream, dds/stream_partition.hpp).
  eprosima::fastdds::dds::Subscriber* patch_subscriber_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  eprosima::fastdds::dds::DataWriter* status_writer_ = nullptr;
  /// topics.diagnostics (null when empty): the status again, for ROS 2's /diagnostics.
  eprosima::fastdds::dds::DataWriter* diagnostics_writer_ = nullptr;
  /// topics.tf (null when empty or without odometry): map -> odom per stream.
  eprosima::fastdds::dds::DataWriter* tf_writer_ = nullptr;
  /// topics.map_cloud (null when empty): the map's points, filled by the mapping thread's
  /// tiles, sent from poll().
  eprosima::fastdds::dds::DataWriter* cloud_writer_ = nullptr;
  std::unique_ptr<MapCloudBuffer> cloud_;
  Clock::time_point next_cloud_{};
  /// topics.map_tiles: fed by the mapping thread, its held tiles flushed by poll().
  std::unique_ptr<MapTilePublisher> tiles_;
  MapOdometryRelay relay_;
  std::map<std::string, OdometryStream> odometry_;
  std::unique_ptr<Sink> sink_;
  std::unique_ptr<MappingWorker> worker_;
  Clock::time_point next_status_{};
  std::uint64_t reported_rejected_ = 0;
  std::uint64_t reported_lost_ = 0;
  bool stopped_ = false;
};

}  // namespace litamin2::aggregator
