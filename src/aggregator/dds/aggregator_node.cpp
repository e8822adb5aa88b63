#include "litamin2/aggregator/dds/aggregator_node.hpp"

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "litamin2/aggregator/dds/aggregator_messages.hpp"
#include "litamin2/aggregator/dds/aggregator_metrics.hpp"
#include "litamin2/aggregator/dds/map_cloud_message.hpp"
#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/participant_setup.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/dds/tile_box_filter.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/dds/transform_conversion.hpp"
#include "litamin2/msg/KeyframePosesPubSubTypes.h"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "litamin2/msg/MapSummaryPubSubTypes.h"
#include "litamin2/msg/MapTilePubSubTypes.h"
#include "litamin2/service/topic_names.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

#include <spdlog/spdlog.h>
#include <cmath>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <algorithm>
#include <stdexcept>

namespace litamin2::aggregator {

namespace fdds = eprosima::fastdds::dds;

namespace {

/// Corrected poses: the latest per stream instance, kept for late readers.
fdds::DataWriterQos latest_per_instance_qos() {
  return dds::latest_per_instance_writer_qos(10'000);  // one instance per stream
}

/// KeyframePoses: one instance per stream chunk (publish.poses_chunk_keyframes), e.g. 100
/// vehicles of 10^4 keyframes in chunks of 256: 4,000.
fdds::DataWriterQos keyframe_poses_qos() {
  return dds::latest_per_instance_writer_qos(100'000);
}

dds::PatchConversionOptions patch_options(const AggregatorConfig& config) {
  dds::PatchConversionOptions options;
  options.max_distributions = static_cast<std::size_t>(config.limits.max_distributions_per_patch);
  return options;
}

/// The largest serialised map patch accepted: 40 bytes a distribution plus 1 MiB for the rest
/// (strings, pose, covariance).
std::uint32_t patch_payload_limit(int max_distributions) {
  const std::uint64_t bytes = 40ull * static_cast<std::uint64_t>(max_distributions) + (1u << 20);
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(bytes, 0xffffffffu));
}

}  // namespace

class AggregatorNode::Sink : public AggregatorSink {
 public:
  Sink(fdds::DataWriter* poses, fdds::DataWriter* summary, MapOdometryRelay& relay,
       MapCloudBuffer* cloud, MapTilePublisher& tiles)
      : poses_(poses), summary_(summary), relay_(relay), cloud_(cloud), tiles_(tiles) {}
  void publish_tile(const TileOutput& tile) override {
    tiles_.offer(tile);
    if (!cloud_) return;
    std::lock_guard lock(cloud_->mutex);
    cloud_->cloud.update(tile);
    cloud_->changed = true;
  }
  void publish_poses(const StreamPoses& poses) override {
    relay_.set_correction(poses.stream, map_correction(poses));
    litamin2::msg::KeyframePoses msg = to_keyframe_poses_msg(poses);
    if (!poses_->write(&msg)) spdlog::warn("cannot publish the poses of stream {}", poses.stream);
  }
  void publish_summary(const MapSummary& summary) override {
    litamin2::msg::MapSummary msg = to_map_summary_msg(summary, dds::wall_clock_now());
    if (!summary_->write(&msg)) spdlog::warn("cannot publish the map summary");
  }

 private:
  fdds::DataWriter* poses_;
  fdds::DataWriter* summary_;
  MapOdometryRelay& relay_;
  MapCloudBuffer* cloud_;
  MapTilePublisher& tiles_;
};

AggregatorNode::AggregatorNode(AggregatorConfig config, const AggregatorCore::Progress& progress)
    : config_(std::move(config)),
      queue_(static_cast<std::size_t>(config_.ingest.queue_capacity)),
      writer_partitions_(config_.topics.map_patches),
      listener_(queue_, patch_options(config_), &writer_partitions_),
      relay_(std::chrono::milliseconds(std::llround(config_.publish.map_frame_settle_s * 1000.0))) {
  store::StoreOptions options;
  options.synchronous_full = config_.store.synchronous_full;
  options.restart_readers = config_.store.restart_readers;
  options.page_size = config_.store.page_size_kb * 1024;
  options.sqlite_cache_mb = config_.store.sqlite_cache_mb;
  CoreOptions core_options;
  core_options.distribution_cache_bytes =
      static_cast<std::size_t>(config_.store.distribution_cache_mb) << 20;
  core_options.tiles = config_.map_tiles.tiles;
  core_options.tile_cache_bytes = static_cast<std::size_t>(config_.map_tiles.cache_mb) << 20;
  core_ = std::make_unique<AggregatorCore>(config_.store.path, store::OpenMode::kCreateIfMissing,
                                           config_.mapper, options, progress, core_options);
  spdlog::info("store {}: {} keyframe(s) of {} stream(s) recovered, {} loop edge(s)",
               config_.store.path, core_->recovered(), core_->mapper().stats().streams,
               core_->mapper().loops().size());

  std::string error;
  participant_ = dds::create_participant(
      dds::participant_config(config_.dds, config_.security, "litamin2-aggregator"), &error,
      &writer_partitions_, fdds::StatusMask::none());
  if (!participant_) throw std::runtime_error("cannot create the DDS participant: " + error);
  // Received patches and odometry are deserialised by CheckedTypes: malformed CDR is counted,
  // not fatal, and a patch's payload is bounded by limits.max_distributions_per_patch.
  const std::uint32_t patch_limit = patch_payload_limit(config_.limits.max_distributions_per_patch);
  checked_patch_type_ = new dds::CheckedType<litamin2::msg::MapPatchPubSubType>(patch_limit);
  // limits.fixed_patch_payloads: the reader's history buffers are of this size, and Fast DDS
  // drops a larger sample before reassembling it (dds::map_patches_reader_qos).
  if (config_.limits.fixed_patch_payloads) checked_patch_type_->m_typeSize = patch_limit;
  patch_type_ = dds::register_type(participant_.get(), checked_patch_type_);
  poses_type_ =
      dds::register_type(participant_.get(), new litamin2::msg::KeyframePosesPubSubType());
  summary_type_ = dds::register_type(participant_.get(), new litamin2::msg::MapSummaryPubSubType());
  status_type_ =
      dds::register_type(participant_.get(), new diagnostic_msgs::msg::DiagnosticArrayPubSubType());
  checked_odometry_type_ = new dds::CheckedType<nav_msgs::msg::OdometryPubSubType>();
  odometry_type_ = dds::register_type(participant_.get(), checked_odometry_type_);

  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  patch_subscriber_ = participant_->create_subscriber(dds::every_stream_subscriber_qos());
  if (!subscriber_ || !publisher_ || !patch_subscriber_)
    throw std::runtime_error("cannot create publisher/subscriber");
  auto topic = [&](const std::string& name, const fdds::TypeSupport& type) {
    fdds::Topic* t =
        participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (!t) throw std::runtime_error("cannot create topic " + name);
    return t;
  };
  fdds::Topic* patches = topic(config_.topics.map_patches, patch_type_);
  // standby.strength > 0: the map outputs are EXCLUSIVE, so that an exclusive reader takes one
  // aggregator's (the strongest live one's) when two run on the same patches. Status and
  // diagnostics stay SHARED (each aggregator reports itself), and so does rt/tf: it is one
  // unkeyed topic that the daemons' odom -> base_link transforms share, so an exclusive rt/tf
  // would hide either those or the standby's map -> odom from every reader.
  fdds::DataWriter* poses_writer = publisher_->create_datawriter(
      topic(config_.topics.keyframe_poses, poses_type_), output_qos(keyframe_poses_qos()));
  fdds::DataWriter* summary_writer = publisher_->create_datawriter(
      topic(config_.topics.map_summary, summary_type_), output_qos(latest_per_instance_qos()));
  status_writer_ = publisher_->create_datawriter(topic(config_.topics.status, status_type_),
                                                 dds::status_writer_qos());
  if (!poses_writer || !summary_writer || !status_writer_)
    throw std::runtime_error("cannot create output writers");
  if (!config_.topics.diagnostics.empty()) {
    diagnostics_writer_ = publisher_->create_datawriter(
        topic(config_.topics.diagnostics, status_type_), dds::diagnostics_writer_qos());
    if (!diagnostics_writer_)
      throw std::runtime_error("cannot create the writer of " + config_.topics.diagnostics);
  }
  if (!config_.topics.tf.empty() && !config_.topics.odometry.empty()) {
    tf_type_ = dds::register_type(participant_.get(), new tf2_msgs::msg::TFMessagePubSubType());
    tf_writer_ =
        publisher_->create_datawriter(topic(config_.topics.tf, tf_type_), dds::tf_writer_qos());
    if (!tf_writer_) throw std::runtime_error("cannot create the writer of " + config_.topics.tf);
  }
  if (!config_.topics.map_cloud.empty()) {
    cloud_type_ =
        dds::register_type(participant_.get(), new sensor_msgs::msg::PointCloud2PubSubType());
    // Transient-local, latest only: a viewer that starts later gets the current map.
    cloud_writer_ = publisher_->create_datawriter(topic(config_.topics.map_cloud, cloud_type_),
                                                  output_qos(dds::tf_static_writer_qos()));
    if (!cloud_writer_)
      throw std::runtime_error("cannot create the writer of " + config_.topics.map_cloud);
    cloud_ = std::make_unique<MapCloudBuffer>();
  }
  // The clients' box filter, so that this writer sends each of them only its tiles.
  if (!dds::register_tile_box_filter(participant_.get()))
    spdlog::warn("cannot register the tile box filter: map tile readers filter themselves");
  tile_type_ = dds::register_type(participant_.get(), new litamin2::msg::MapTilePubSubType());
  fdds::DataWriter* tile_writer = publisher_->create_datawriter(
      topic(config_.topics.map_tiles, tile_type_), output_qos(dds::map_tiles_writer_qos()));
  if (!tile_writer)
    throw std::runtime_error("cannot create the writer of " + config_.topics.map_tiles);
  // Revisions follow the wall clock's microseconds: above the previous run's, and comparable
  // with a standby's.
  tiles_ = std::make_unique<MapTilePublisher>(
      [tile_writer](litamin2::msg::MapTile& msg) { return tile_writer->write(&msg); },
      config_.map_tiles.publish_period_s,
      [] { return static_cast<std::uint64_t>(dds::wall_clock_now().nanoseconds / 1000); });
  sink_ = std::make_unique<Sink>(poses_writer, summary_writer, relay_, cloud_.get(), *tiles_);
  worker_ = std::make_unique<MappingWorker>(*core_, queue_, *sink_, config_);
  relay_.start();
  worker_->start();
  subscribe_odometry(worker_->status());

  reader_ = patch_subscriber_->create_datareader(
      patches, dds::map_patches_reader_qos(config_.limits.fixed_patch_payloads), &listener_,
      fdds::StatusMask::data_available()
          << fdds::StatusMask::subscription_matched() << fdds::StatusMask::sample_lost());
  if (!reader_) throw std::runtime_error("cannot create the map patch reader");
  next_status_ = Clock::now();
  spdlog::info(
      "DDS participant up: domain {} ({}), profile {}, reading {}, publishing {}, {} and {}",
      config_.dds.domain, service::to_string(config_.dds.domain_source),
      service::to_string(config_.dds.profile), config_.topics.map_patches,
      config_.topics.keyframe_poses, config_.topics.map_summary, config_.topics.map_tiles);
  if (config_.standby.strength > 0)
    spdlog::info(
        "hot standby: map outputs EXCLUSIVE at strength {} (exclusive readers take the "
        "strongest live aggregator's)",
        config_.standby.strength);
}

fdds::DataWriterQos AggregatorNode::output_qos(fdds::DataWriterQos qos) const {
  return dds::with_ownership_strength(std::move(qos),
                                      static_cast<std::uint32_t>(config_.standby.strength));
}

AggregatorNode::~AggregatorNode() {
  shutdown();
  worker_.reset();
  participant_.reset();
}

void AggregatorNode::subscribe_odometry(const WorkerStatus& status) {
  if (config_.topics.odometry.empty()) return;
  const auto in = service::TopicPattern::parse(config_.topics.odometry);
  const auto out = service::TopicPattern::parse(config_.topics.map_odometry);
  if (!in || !out) return;  // rejected by the config already
  for (const auto& [stream, counts] : status.streams) {
    if (odometry_.count(stream)) continue;
    OdometryStream& o = odometry_[stream];
    const std::string in_topic = in->topic_for(stream), out_topic = out->topic_for(stream);
    fdds::Topic* in_t = participant_->create_topic(in_topic, odometry_type_.get_type_name(),
                                                   fdds::TOPIC_QOS_DEFAULT);
    fdds::Topic* out_t = participant_->create_topic(out_topic, odometry_type_.get_type_name(),
                                                    fdds::TOPIC_QOS_DEFAULT);
    fdds::DataWriter* writer =
        out_t ? publisher_->create_datawriter(out_t, output_qos(dds::odom_writer_qos())) : nullptr;
    if (!in_t || !writer) {
      spdlog::warn("stream {}: cannot create {} / {}: no map-frame odometry", stream, in_topic,
                   out_topic);
      continue;
    }
    MapOdometryRelay::PublishTransform publish_transform;
    if (tf_writer_) {
      fdds::DataWriter* tf_writer = tf_writer_;
      publish_transform = [tf_writer, stream](const geometry_msgs::msg::TransformStamped& t) {
        tf2_msgs::msg::TFMessage msg = dds::to_tf_message(t);
        if (!tf_writer->write(&msg)) spdlog::warn("cannot publish the map transform of {}", stream);
      };
    }
    relay_.add_stream(
        stream,
        [writer, stream](const nav_msgs::msg::Odometry& msg) {
          nav_msgs::msg::Odometry copy = msg;
          if (!writer->write(&copy))
            spdlog::warn("cannot publish the map-frame odometry of {}", stream);
        },
        std::move(publish_transform));
    o.listener = std::make_unique<OdometryListener>(stream, relay_);
    o.reader = subscriber_->create_datareader(in_t,
                                              config_.ingest.exclusive_odometry
                                                  ? dds::exclusive_odom_reader_qos()
                                                  : dds::odom_reader_qos(),
                                              o.listener.get(), fdds::StatusMask::data_available());
    if (!o.reader) {
      spdlog::warn("stream {}: cannot read {}", stream, in_topic);
      continue;
    }
    spdlog::info("stream {}: reading {}, publishing its map-frame pose on {}", stream, in_topic,
                 out_topic);
  }
}

void AggregatorNode::poll(Clock::time_point now) {
  if (stopped_) return;
  const WorkerStatus w = worker_->status();
  if (w.streams.size() > odometry_.size()) subscribe_odometry(w);
  tiles_->flush_due(now);
  if (cloud_ && now >= next_cloud_) publish_map_cloud(now);
  if (now < next_status_) return;
  publish_status(now);
  next_status_ = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(config_.publish.status_period_s));
}

void AggregatorNode::publish_map_cloud(Clock::time_point now) {
  std::vector<MapPoint> points;
  {
    std::lock_guard lock(cloud_->mutex);
    if (!cloud_->changed) return;
    cloud_->changed = false;
    points = cloud_->cloud.points();
  }
  // The tiles are in the map frame (the anchor stream's odometry frame, TileOutput::anchor).
  sensor_msgs::msg::PointCloud2 msg = to_map_cloud_msg(points, dds::wall_clock_now(), kMapFrame);
  if (!cloud_writer_->write(&msg)) spdlog::warn("cannot publish {}", config_.topics.map_cloud);
  next_cloud_ = now + std::chrono::duration_cast<Clock::duration>(
                          std::chrono::duration<double>(config_.publish.tiles_period_s));
}

bool AggregatorNode::healthy(Clock::time_point now) const {
  if (worker_->failed()) return false;
  if (!config_.watchdog.enabled) return true;
  return worker_->healthy(std::chrono::duration<double>(config_.watchdog.stall_timeout_s), now);
}

bool AggregatorNode::failed() const {
  return worker_->failed();
}

WorkerStatus AggregatorNode::status() const {
  return worker_->status();
}

std::string AggregatorNode::summary() const {
  const WorkerStatus s = worker_->status();
  return fmt::format("{} keyframe(s) of {} stream(s), {} loop(s), {} duplicate(s), {} queued",
                     s.keyframes, s.streams.size(), s.loops, s.duplicates, queue_.size());
}

IngestCounters AggregatorNode::ingest_counters() const {
  IngestCounters in;
  in.received = listener_.received();
  in.rejected = listener_.rejected();
  in.rejected_by_reason = listener_.rejected_by_reason();
  in.malformed_samples = checked_patch_type_->failures() + checked_odometry_type_->failures();
  in.samples_lost = listener_.samples_lost();
  in.writers = listener_.writers();
  in.queued = queue_.size();
  in.queue_capacity = queue_.capacity();
  in.queue_high_water = queue_.high_water();
  in.store_path = config_.store.path;
  const MapTileCounters tiles = tiles_->counters();
  in.map_tiles_published = tiles.published;
  in.map_tiles_deferred = tiles.deferred;
  return in;
}

std::string AggregatorNode::metrics_text() const {
  return aggregator_metrics_text(worker_->status(), ingest_counters(), relay_.status(),
                                 store_size_bytes(config_.store.path));
}

void AggregatorNode::publish_status(Clock::time_point now) {
  const WorkerStatus w = worker_->status();
  const IngestCounters in = ingest_counters();
  std::uint8_t level = 0;
  std::string message = "ok";
  if (!w.error.empty()) {
    level = 2;
    message = "store failed: " + w.error;
  } else if (!healthy(now)) {
    level = 2;
    message = "mapping stalled";
  } else if (in.rejected > reported_rejected_) {
    level = 1;
    message = "bad map patches received";
  } else if (in.samples_lost > reported_lost_) {
    level = 1;
    message = "map patches lost";
  }
  reported_rejected_ = in.rejected;
  reported_lost_ = in.samples_lost;
  auto msg = make_aggregator_status(w, in, relay_.status(), level, message, dds::wall_clock_now());
  status_writer_->write(&msg);
  if (diagnostics_writer_) diagnostics_writer_->write(&msg);
}

void AggregatorNode::shutdown() {
  if (stopped_) return;
  stopped_ = true;
  if (reader_) {
    // The worker still runs, so a listener waiting on a full queue gets through.
    reader_->set_listener(nullptr);
    patch_subscriber_->delete_datareader(reader_);
    reader_ = nullptr;
  }
  for (auto& [stream, o] : odometry_) {
    if (!o.reader) continue;
    o.reader->set_listener(nullptr);
    subscriber_->delete_datareader(o.reader);
    o.reader = nullptr;
  }
  const std::size_t queued = queue_.size();
  worker_->stop();
  // The worker's last turn handed its tiles over; the ones held by the period go out now.
  tiles_->flush_all();
  const MapTileCounters tiles = tiles_->counters();
  spdlog::info(
      "map tiles: {} sample(s) published, {} deferred ({} folded), {} write failure(s); the "
      "writer's box filter evaluated {} sample(s) for readers, passed {}",
      tiles.published, tiles.deferred, tiles.folded, tiles.write_failures,
      dds::tile_box_evaluations(), dds::tile_box_passed());
  relay_.stop();
  publish_status(Clock::now());
  spdlog::info("shut down: {} queued patch(es) committed; {}", queued, summary());
  const WorkerStatus w = worker_->status();
  const IngestCpu& in = w.ingest_cpu;
  const mapping::MapperCpu& m = w.mapper_cpu;
  spdlog::info(
      "CPU by stage, s: DDS take {:.2f}, conversion {:.2f}; sort {:.2f}, store {:.2f}, "
      "regularize {:.2f}, add_keyframe {:.2f} (descriptor {:.2f}, chain {:.2f}, proximity "
      "{:.2f}, descriptor search {:.2f}, verification {:.2f}), optimize {:.2f}, save graph "
      "{:.2f}; poses {:.2f}, summary {:.2f}",
      listener_.take_cpu_s(), listener_.convert_cpu_s(), in.sort_s, in.store_s, in.regularize_s,
      in.add_keyframe_s, m.descriptor_s, m.chain_s, m.proximity_s, m.descriptor_search_s,
      m.verification_s, in.optimize_s, in.save_graph_s, w.poses_cpu_s, w.summary_cpu_s);
}

}  // namespace litamin2::aggregator
