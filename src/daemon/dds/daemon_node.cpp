#include "litamin2/daemon/dds/daemon_node.hpp"

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "litamin2/daemon/dds/daemon_metrics.hpp"
#include "litamin2/daemon/dds/dds_stream_sink.hpp"
#include "litamin2/daemon/dds/plain_scan_listener.hpp"
#include "litamin2/daemon/dds/points_listener.hpp"
#include "litamin2/daemon/dds/status_message.hpp"
#include "litamin2/daemon/merged_input.hpp"
#include "litamin2/daemon/stream_frames.hpp"
#include "litamin2/daemon/stream_processor.hpp"
#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/key_locked_type.hpp"
#include "litamin2/dds/participant_setup.hpp"
#include "litamin2/dds/pointcloud2_scan_type.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/dds/transform_conversion.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "litamin2_zero_copy/msg/PlainScanPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

#include <spdlog/fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

/// One input topic of a stream: the stream's only one, or one sensor of several.
struct DaemonNode::Input {
  std::string topic;
  fdds::Topic* points_topic = nullptr;
  std::unique_ptr<PointsListener> listener;
  fdds::DataReader* reader = nullptr;
  bool reliable = false;
};

struct DaemonNode::Stream {
  StreamConfig config;
  StreamStats stats;
  fdds::DataWriter* odom_writer = nullptr;
  /// The stream's map patches: a publisher whose partition is the stream id, and its writer.
  fdds::Publisher* patch_publisher = nullptr;
  fdds::DataWriter* patch_writer = nullptr;
  std::unique_ptr<DdsStreamSink> sink;
  /// Replaced when a stream moves back here (sharding): guarded against the worker running a
  /// frame.
  std::mutex processor_mutex;
  std::unique_ptr<StreamProcessor> processor;
  /// Sharding: the member tracking this stream now, when it is not this daemon.
  std::string moved_to;
  /// Hot standby: this daemon's rank for the stream when set_role last ran (0: owner).
  std::optional<std::size_t> rank;
  StreamScheduler::Handle handle = 0;
  /// One per input topic (config.topic, or each of config.inputs).
  std::vector<Input> inputs;
  /// Several sensors: their scans merged into the frames queued on `handle`.
  std::unique_ptr<MergedInput> merged;
  /// The opt-in zero-copy input (config.zero_copy_topic): read from the start, whatever
  /// discovery reports, until shutdown.
  std::unique_ptr<PlainScanListener> zero_copy_listener;
  fdds::DataReader* zero_copy_reader = nullptr;
  std::uint64_t reported_dropped = 0;
  std::uint64_t reported_missing = 0;
  std::uint64_t reported_bad = 0;
  std::uint64_t reported_out_of_order = 0;
};

DaemonNode::DaemonNode(DaemonConfig config) : config_(std::move(config)) {
  if (config_.discovery.enabled) {
    std::string error;
    pattern_ = service::TopicPattern::parse(config_.discovery.pattern, &error);
    if (!pattern_) throw ConfigError("discovery.pattern: " + error);
  }
  // The scheduling (opt-in) is applied before any thread of the node starts, so that with scope
  // process Fast DDS's threads and the workers inherit it from this one: a real-time policy
  // that the process may not use fails start-up, before DDS starts.
  if (config_.scheduling.scope == SchedulingScope::kProcess)
    apply_worker_scheduling(pthread_self(), config_.scheduling,
                            "the daemon's threads (scope process)");
  // Trackers of configured streams are built first: an invalid config fails before DDS starts.
  scheduler_ = std::make_unique<StreamScheduler>(
      config_.threads, static_cast<std::size_t>(config_.queue_depth), config_.scheduling);
  scheduler_->set_error_handler([](const std::string& stream, const std::string& what) {
    spdlog::error("stream {}: frame failed: {}", stream, what);
  });

  sensor_msgs::msg::PointCloud2PubSubType points_type_probe;
  discovery_ = std::make_unique<PublisherDiscovery>(points_type_probe.getName());
  std::string error;
  dds::ParticipantConfig participant_config =
      dds::participant_config(config_.dds, config_.security, "litamin2d");
  if (config_.sharding.enabled) {
    membership_.emplace(resolved_member_id(config_));
    participant_config.user_data = member_user_data(membership_->self());
  }
  participant_ = dds::create_participant(participant_config, &error, discovery_.get(),
                                         fdds::StatusMask::none());
  if (!participant_) throw std::runtime_error("cannot create the DDS participant: " + error);
  {
    std::ostringstream guid;
    guid << participant_->guid().guidPrefix;
    own_participant_ = guid.str();
  }

  // Received scans are converted while they are deserialised (PointCloud2ScanType): malformed
  // CDR is counted, not fatal, as with CheckedType.
  points_type_ = dds::register_type(participant_.get(), new dds::PointCloud2ScanType());
  odom_type_ = dds::register_type(participant_.get(), new nav_msgs::msg::OdometryPubSubType());
  // Stream workers write map patches concurrently: the generated getKey() is not thread-safe.
  map_patch_type_ = dds::register_type(participant_.get(),
                                       new dds::KeyLockedType<litamin2::msg::MapPatchPubSubType>());
  status_type_ =
      dds::register_type(participant_.get(), new diagnostic_msgs::msg::DiagnosticArrayPubSubType());

  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  if (!subscriber_ || !publisher_) throw std::runtime_error("cannot create publisher/subscriber");

  patches_topic_ = participant_->create_topic(
      config_.outputs.map_patches_topic, map_patch_type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* status_topic = participant_->create_topic(
      config_.outputs.status_topic, status_type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (!patches_topic_ || !status_topic) throw std::runtime_error("cannot create output topics");
  status_writer_ = publisher_->create_datawriter(status_topic, dds::status_writer_qos());
  if (!status_writer_) throw std::runtime_error("cannot create output writers");
  if (!config_.outputs.diagnostics_topic.empty()) {
    auto* diagnostics_topic = participant_->create_topic(
        config_.outputs.diagnostics_topic, status_type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (!diagnostics_topic)
      throw std::runtime_error("cannot create topic " + config_.outputs.diagnostics_topic);
    diagnostics_writer_ =
        publisher_->create_datawriter(diagnostics_topic, dds::diagnostics_writer_qos());
    if (!diagnostics_writer_)
      throw std::runtime_error("cannot create the writer of " + config_.outputs.diagnostics_topic);
  }
  if (config_.outputs.publish_tf) {
    tf_type_ = dds::register_type(participant_.get(), new tf2_msgs::msg::TFMessagePubSubType());
    auto* tf_topic = participant_->create_topic(config_.outputs.tf_topic, tf_type_.get_type_name(),
                                                fdds::TOPIC_QOS_DEFAULT);
    auto* tf_static_topic = participant_->create_topic(
        config_.outputs.tf_static_topic, tf_type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (!tf_topic || !tf_static_topic) throw std::runtime_error("cannot create the tf topics");
    tf_writer_ = publisher_->create_datawriter(tf_topic, dds::tf_writer_qos());
    tf_static_writer_ = publisher_->create_datawriter(tf_static_topic, dds::tf_static_writer_qos());
    if (!tf_writer_ || !tf_static_writer_) throw std::runtime_error("cannot create the tf writers");
  }

  for (const StreamConfig& stream : config_.streams) add_stream(stream);
  if (membership_) {
    handover_.set_map_patches_topic(config_.outputs.map_patches_topic);
    handover_.set_map_seed_limits(
        MapSeedLimits{static_cast<std::size_t>(config_.sharding.seed_keyframes),
                      config_.sharding.seed_max_age_s});
    // The patches are in one partition per stream: read them all.
    patch_ids_subscriber_ = participant_->create_subscriber(dds::every_stream_subscriber_qos());
    patch_ids_reader_ = patch_ids_subscriber_ ? patch_ids_subscriber_->create_datareader(
                                                    patches_topic_, dds::map_patch_ids_reader_qos(),
                                                    &handover_, fdds::StatusMask::data_available())
                                              : nullptr;
    if (!patch_ids_reader_) throw std::runtime_error("cannot create the map patch id reader");
    claim_after_ =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(config_.sharding.startup_wait_s));
    spdlog::info("sharding: member {}, claiming streams after {} s", membership_->self(),
                 config_.sharding.startup_wait_s);
  }
  next_status_ = Clock::now();
  spdlog::info("DDS participant up: domain {} ({}), profile {}, {} configured stream(s){}",
               config_.dds.domain, service::to_string(config_.dds.domain_source),
               to_string(config_.dds.profile), config_.streams.size(),
               pattern_ ? ", discovering " + pattern_->str() : std::string());
}

DaemonNode::~DaemonNode() {
  shutdown();
  scheduler_.reset();
  participant_.reset();  // deletes readers, writers and topics
  streams_.clear();
  discovery_.reset();
}

DaemonNode::Stream& DaemonNode::add_stream(StreamConfig config, std::optional<HandoverSeed> seed) {
  auto stream = std::make_unique<Stream>();
  stream->config = std::move(config);
  Stream& s = *stream;
  const std::string odom_topic_name = "rt/" + s.config.id + "/" + config_.outputs.odom_suffix;
  if (s.config.inputs.empty()) {
    s.inputs.resize(1);
    s.inputs[0].topic = s.config.topic;
  } else {
    s.inputs.resize(s.config.inputs.size());
    for (std::size_t i = 0; i < s.inputs.size(); ++i) s.inputs[i].topic = s.config.inputs[i].topic;
  }
  for (Input& input : s.inputs) {
    input.points_topic = topic(input.topic, points_type_.get_type_name());
    if (!input.points_topic)
      throw std::runtime_error("stream " + s.config.id + ": cannot create topic " + input.topic);
  }
  auto* odom_topic = topic(odom_topic_name, odom_type_.get_type_name());
  if (!odom_topic) throw std::runtime_error("stream " + s.config.id + ": cannot create its topics");
  // Hot standby: every tracking daemon writes the odometry, readers take the strongest's;
  // set_role gives the strength.
  s.odom_writer = publisher_->create_datawriter(odom_topic, config_.sharding.replicas > 1
                                                                ? dds::exclusive_odom_writer_qos(1)
                                                                : dds::odom_writer_qos());
  if (!s.odom_writer) throw std::runtime_error("stream " + s.config.id + ": no odom writer");
  // The stream's patches in the partition of its id (dds/stream_partition.hpp): with
  // DDS-Security, Fast DDS refuses the writer unless the permissions grant the partition.
  s.patch_publisher = participant_->create_publisher(dds::stream_publisher_qos(s.config.id));
  s.patch_writer =
      s.patch_publisher
          ? s.patch_publisher->create_datawriter(
                patches_topic_, dds::map_patches_writer_qos(config_.outputs.map_patch_history))
          : nullptr;
  if (!s.patch_writer) {
    if (s.patch_publisher) participant_->delete_publisher(s.patch_publisher);
    publisher_->delete_datawriter(s.odom_writer);
    throw std::runtime_error("stream " + s.config.id + ": cannot create its writer of " +
                             config_.outputs.map_patches_topic + " in partition " + s.config.id +
                             " (refused by the permissions?)");
  }
  const StreamFrames frames = stream_frames(config_.outputs, s.config);
  s.sink = std::make_unique<DdsStreamSink>(s.odom_writer, s.patch_writer, tf_writer_, frames);
  if (tf_static_writer_) {
    // One transient-local message holds every stream's base -> sensor (keep-last 1, as ROS 2's
    // static broadcaster): a new stream republishes the whole set.
    if (s.config.inputs.empty()) {
      static_transforms_.transforms().push_back(dds::to_transform_stamped(
          s.config.extrinsic, dds::wall_clock_now(), frames.base, frames.sensor));
    } else {
      // Several sensors: base -> "<sensor>_<i>" for each, by its extrinsic.
      for (std::size_t i = 0; i < s.config.inputs.size(); ++i)
        static_transforms_.transforms().push_back(
            dds::to_transform_stamped(s.config.inputs[i].extrinsic, dds::wall_clock_now(),
                                      frames.base, frames.sensor + "_" + std::to_string(i)));
    }
    if (!tf_static_writer_->write(&static_transforms_))
      spdlog::warn("stream {}: writing {} failed", s.config.id, config_.outputs.tf_static_topic);
  }
  start_processor(s, std::move(seed));
  Stream* sp = &s;
  s.handle = scheduler_->add_stream(s.config.id, [sp](Frame& f) {
    std::lock_guard lock(sp->processor_mutex);
    sp->processor->process(f);
  });
  // LiTAMIN2 uses only x, y, z (the intensity field is not read), and the per-point time when
  // the stream deskews (tracker.deskew.enabled): a malformed or out-of-sweep time field is a
  // bad message, counted and dropped.
  dds::CloudConversionOptions conversion;
  conversion.read_intensity = false;
  conversion.read_time = s.config.tracker.deskew.enabled;
  conversion.max_points = static_cast<std::size_t>(config_.limits.max_points_per_scan);
  if (s.config.inputs.empty()) {
    s.inputs[0].listener =
        std::make_unique<PointsListener>(s.config.id, *scheduler_, s.handle, s.stats, conversion);
  } else {
    std::vector<Eigen::Isometry3d> extrinsics;
    for (const SensorInput& input : s.config.inputs) extrinsics.push_back(input.extrinsic);
    s.merged =
        std::make_unique<MergedInput>(std::move(extrinsics), s.config.merge, *scheduler_, s.handle);
    MergedInput* merged = s.merged.get();
    for (std::size_t i = 0; i < s.inputs.size(); ++i)
      s.inputs[i].listener = std::make_unique<PointsListener>(
          s.config.id + " input " + s.inputs[i].topic,
          [merged, i](Frame frame) { merged->add(i, std::move(frame)); },
          [merged] { merged->restart(); }, s.stats, conversion);
  }
  if (!s.config.zero_copy_topic.empty()) attach_zero_copy_reader(s, conversion);
  spdlog::info("stream {}: {} -> {}{}", s.config.id, input_topics(s), odom_topic_name,
               tf_writer_
                   ? fmt::format(", tf {} -> {} -> {}", frames.odom, frames.base, frames.sensor)
                   : std::string());
  streams_.push_back(std::move(stream));
  return s;
}

void DaemonNode::attach_zero_copy_reader(Stream& s, const dds::CloudConversionOptions& conversion) {
  if (plain_scan_type_.empty())
    plain_scan_type_ =
        dds::register_type(participant_.get(), new litamin2_zero_copy::msg::PlainScanPubSubType());
  auto* zero_copy_topic = topic(s.config.zero_copy_topic, plain_scan_type_.get_type_name());
  if (!zero_copy_topic)
    throw std::runtime_error("stream " + s.config.id + ": cannot create topic " +
                             s.config.zero_copy_topic);
  s.zero_copy_listener = std::make_unique<PlainScanListener>(*s.inputs[0].listener, conversion);
  s.zero_copy_reader = subscriber_->create_datareader(
      zero_copy_topic, dds::zero_copy_reader_qos(), s.zero_copy_listener.get(),
      fdds::StatusMask::data_available() << fdds::StatusMask::subscription_matched());
  if (!s.zero_copy_reader)
    throw std::runtime_error("stream " + s.config.id + ": cannot create a reader of " +
                             s.config.zero_copy_topic);
  spdlog::info("stream {}: reading {} (zero-copy, litamin2_zero_copy/PlainScan, data-sharing)",
               s.config.id, s.config.zero_copy_topic);
}

fdds::Topic* DaemonNode::topic(const std::string& name, const std::string& type) {
  // The handover's odometry reader (sharding) may have made the stream's odom topic already.
  if (auto* existing = participant_->lookup_topicdescription(name))
    return dynamic_cast<fdds::Topic*>(existing);
  return participant_->create_topic(name, type, fdds::TOPIC_QOS_DEFAULT);
}

void DaemonNode::start_processor(Stream& s, std::optional<HandoverSeed> seed) {
  auto processor = seed ? std::make_unique<StreamProcessor>(s.config, *s.sink, s.stats, *seed,
                                                            config_.sharding.max_extrapolation_s)
                        : std::make_unique<StreamProcessor>(s.config, *s.sink, s.stats);
  std::lock_guard lock(s.processor_mutex);
  s.processor = std::move(processor);
}

DaemonNode::Stream* DaemonNode::find_by_id(const std::string& id) {
  for (auto& s : streams_)
    if (s->config.id == id) return s.get();
  return nullptr;
}

std::optional<HandoverSeed> DaemonNode::handover_seed(const std::string& id) const {
  return handover_.seed(id);
}

void DaemonNode::on_sharded_writer(const DiscoveredWriter& writer) {
  const std::optional<std::string> id = pattern_->match(writer.topic);
  if (!id) return;
  auto it = known_.find(*id);
  if (it == known_.end()) {
    if (known_.size() >= static_cast<std::size_t>(config_.discovery.max_streams)) {
      spdlog::warn("ignoring {}: discovery.max_streams ({}) reached", writer.topic,
                   config_.discovery.max_streams);
      return;
    }
    it = known_.emplace(*id, KnownStream{writer.topic, writer.reliable, nullptr}).first;
    // Every known stream's odometry, whoever tracks it: the seed if it moves here.
    const std::string odom = "rt/" + *id + "/" + config_.outputs.odom_suffix;
    handover_.add_stream(*id, odom);
    auto* topic =
        participant_->create_topic(odom, odom_type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (topic)
      it->second.odom_reader = subscriber_->create_datareader(
          topic,
          config_.sharding.replicas > 1 ? dds::exclusive_odom_reader_qos(1)
                                        : dds::odom_reader_qos(1),
          &handover_, fdds::StatusMask::data_available());
    if (!it->second.odom_reader)
      spdlog::warn("stream {}: cannot read {}: a takeover would start a new odometry frame", *id,
                   odom);
  } else if (it->second.topic != writer.topic) {
    spdlog::warn("ignoring {}: stream id {} is taken by {}", writer.topic, *id, it->second.topic);
    return;
  } else if (!writer.reliable && it->second.reliable) {
    it->second.reliable = false;
    if (Stream* s = find_by_id(*id); s && s->inputs[0].reader && s->inputs[0].reliable) {
      spdlog::warn("stream {}: a best-effort publisher appeared; reading best-effort", *id);
      detach_reader(*s);
      attach_reader(*s, s->inputs[0], false);
    }
  }
}

void DaemonNode::reshard(Clock::time_point now) {
  if (!membership_ || now < claim_after_) return;
  if (!claiming_) {
    claiming_ = true;
    spdlog::info("sharding: live members {}", fmt::join(membership_->live(), ", "));
  }
  const auto replicas = static_cast<std::size_t>(config_.sharding.replicas);
  for (const auto& [id, known] : known_) {
    const std::size_t rank = membership_->rank(id);
    Stream* s = find_by_id(id);
    if (rank < replicas) {
      if (s && reading(*s)) {
        set_role(*s, rank);
        continue;
      }
      std::optional<HandoverSeed> seed = handover_seed(id);
      if (seed) {
        ++takeovers_;
        spdlog::info(
            "stream {}: tracked here from the last pose ({:.2f}, {:.2f}, {:.2f}) at {}.{:09d}, "
            "keyframe ids from {}, map from {} patch(es){}",
            id, seed->pose.translation().x(), seed->pose.translation().y(),
            seed->pose.translation().z(), seed->stamp.nanoseconds / 1'000'000'000,
            seed->stamp.nanoseconds % 1'000'000'000, seed->next_keyframe_id,
            seed->map_keyframes.size(),
            seed->map_keyframes.empty()
                ? std::string()
                : fmt::format(" (ids {}..{})", seed->map_keyframes.front().key.id,
                              seed->map_keyframes.back().key.id));
      } else {
        spdlog::info("stream {}: tracked here (no earlier odometry seen)", id);
      }
      if (!s) {
        s = &add_stream(discovered_stream(config_, id, known.topic), std::move(seed));
      } else {
        start_processor(*s, std::move(seed));
      }
      s->moved_to.clear();
      s->rank.reset();
      set_role(*s, rank);
      attach_reader(*s, s->inputs[0], known.reliable);
    } else if (s && reading(*s)) {
      const std::string owner = membership_->owner(id);
      spdlog::info("stream {}: moved to member {}", id, owner);
      detach_reader(*s);
      s->moved_to = owner;
      // A standby's held patches belong to the tracker that stops here: none is published if
      // the stream comes back (its new tracker starts from the handover seed).
      if (s->sink->holding()) s->sink->release(std::numeric_limits<std::uint64_t>::max());
    }
  }
}

void DaemonNode::set_role(Stream& s, std::size_t rank) {
  if (config_.sharding.replicas <= 1) return;
  const std::string& id = s.config.id;
  if (s.rank == rank) {
    if (rank > 0) s.sink->drop_held_before(handover_.next_keyframe_id(id));
    return;
  }
  fdds::DataWriterQos qos = s.odom_writer->get_qos();
  qos.ownership_strength().value = static_cast<std::uint32_t>(config_.sharding.replicas - rank);
  if (s.odom_writer->set_qos(qos) != ReturnCode_t::RETCODE_OK)
    spdlog::error("stream {}: cannot set the odometry writer's ownership strength to {}", id,
                  qos.ownership_strength().value);
  if (rank == 0) {
    if (s.sink->holding()) {
      const std::uint64_t first = handover_.next_keyframe_id(id);
      const std::size_t written = s.sink->release(first);
      spdlog::info(
          "stream {}: owned here now (strength {}); {} held map patch(es) from id {} "
          "published",
          id, qos.ownership_strength().value, written, first);
    } else {
      spdlog::info("stream {}: owned here (strength {})", id, qos.ownership_strength().value);
    }
  } else {
    s.sink->hold(static_cast<std::size_t>(config_.outputs.map_patch_history));
    spdlog::info(
        "stream {}: standby {} here (strength {}): map patches held until it owns the "
        "stream",
        id, rank, qos.ownership_strength().value);
  }
  s.rank = rank;
}

std::vector<std::string> DaemonNode::members() const {
  return membership_ ? membership_->live() : std::vector<std::string>{};
}

std::pair<DaemonNode::Stream*, DaemonNode::Input*> DaemonNode::find_by_topic(
    const std::string& topic) {
  for (auto& s : streams_)
    for (Input& input : s->inputs)
      if (input.topic == topic) return {s.get(), &input};
  return {nullptr, nullptr};
}

bool DaemonNode::reading(const Stream& s) {
  for (const Input& input : s.inputs)
    if (input.reader) return true;
  return false;
}

std::string DaemonNode::input_topics(const Stream& s) {
  std::string topics;
  for (const Input& input : s.inputs) topics += (topics.empty() ? "" : ",") + input.topic;
  return topics;
}

void DaemonNode::attach_reader(Stream& s, Input& input, bool reliable) {
  input.reader = subscriber_->create_datareader(
      input.points_topic, dds::points_reader_qos(reliable), input.listener.get(),
      fdds::StatusMask::data_available()
          << fdds::StatusMask::subscription_matched() << fdds::StatusMask::sample_lost());
  if (!input.reader) {
    spdlog::error("stream {}: cannot create a reader of {}", s.config.id, input.topic);
    return;
  }
  input.reliable = reliable;
  spdlog::info("stream {}: reading {} ({})", s.config.id, input.topic,
               reliable ? "reliable" : "best effort");
}

void DaemonNode::detach_reader(Input& input) {
  if (!input.reader) return;
  input.reader->set_listener(nullptr);
  subscriber_->delete_datareader(input.reader);
  input.reader = nullptr;
}

void DaemonNode::detach_reader(Stream& s) {
  for (Input& input : s.inputs) detach_reader(input);
}

void DaemonNode::on_writer(const DiscoveredWriter& writer) {
  if (membership_) {
    on_sharded_writer(writer);
    return;
  }
  auto [s, input] = find_by_topic(writer.topic);
  if (!s) {
    if (!pattern_) return;
    const std::optional<std::string> id = pattern_->match(writer.topic);
    if (!id) {
      spdlog::debug("ignoring {}: does not match {}", writer.topic, pattern_->str());
      return;
    }
    if (streams_.size() >= static_cast<std::size_t>(config_.discovery.max_streams)) {
      spdlog::warn("ignoring {}: discovery.max_streams ({}) reached", writer.topic,
                   config_.discovery.max_streams);
      return;
    }
    for (const auto& other : streams_)
      if (other->config.id == *id) {
        spdlog::warn("ignoring {}: stream id {} is taken by {}", writer.topic, *id,
                     input_topics(*other));
        return;
      }
    s = &add_stream(discovered_stream(config_, *id, writer.topic));
    input = &s->inputs[0];
  }
  if (!input->reader) {
    attach_reader(*s, *input, writer.reliable);
  } else if (input->reliable && !writer.reliable) {
    // A reliable reader does not match a best-effort writer: read everything best-effort.
    spdlog::warn("stream {}: a best-effort publisher of {} appeared; reading it best-effort",
                 s->config.id, input->topic);
    detach_reader(*input);
    attach_reader(*s, *input, false);
  }
}

void DaemonNode::poll(Clock::time_point now) {
  if (stopped_) return;
  for (const DiscoveredWriter& writer : discovery_->take()) {
    try {
      on_writer(writer);
    } catch (const std::exception& e) {
      spdlog::error("cannot start a stream for {}: {}", writer.topic, e.what());
    }
  }
  if (membership_) {
    bool changed = false;
    for (const ParticipantEvent& event : discovery_->take_participants()) {
      if (event.participant == own_participant_) continue;
      changed = (event.alive ? membership_->discovered(event.participant, event.user_data)
                             : membership_->lost(event.participant)) ||
                changed;
    }
    if (membership_->rejected() > reported_rejected_members_) {
      spdlog::warn("sharding: {} participant announcement(s) with an invalid member id rejected",
                   membership_->rejected() - reported_rejected_members_);
      reported_rejected_members_ = membership_->rejected();
    }
    if (changed && claiming_)
      spdlog::info("sharding: live members {}", fmt::join(membership_->live(), ", "));
    try {
      reshard(now);
    } catch (const std::exception& e) {
      spdlog::error("sharding: cannot start a stream: {}", e.what());
    }
  }
  for (auto& s : streams_)
    if (s->merged) s->merged->expire(now);
  if (now >= next_status_) {
    publish_status(now);
    next_status_ = now + std::chrono::duration_cast<Clock::duration>(
                             std::chrono::duration<double>(config_.outputs.status_period_s));
  }
}

bool DaemonNode::healthy(Clock::time_point now) const {
  if (!config_.watchdog.enabled) return true;
  return scheduler_->longest_in_flight(now) <
         std::chrono::duration<double>(config_.watchdog.stall_timeout_s);
}

std::vector<StreamStatus> DaemonNode::status(Clock::time_point now) const {
  std::vector<StreamStatus> statuses;
  for (const auto& s : streams_) {
    StreamStatus st;
    st.id = s->config.id;
    st.topic = input_topics(*s);
    st.stats = s->stats.snapshot(now);
    st.counters = scheduler_->counters(s->handle);
    st.stats.frames_dropped = st.counters.dropped;  // the queue counts drops
    st.stats.frames_failed = st.counters.failed;
    st.reading = reading(*s);
    // Reliable when every input read is.
    st.reliable = st.reading;
    for (const Input& input : s->inputs) {
      if (input.reader && !input.reliable) st.reliable = false;
      st.samples_lost += input.listener->samples_lost();
    }
    if (s->merged) st.merge = s->merged->counters();
    st.moved_to = s->moved_to;
    statuses.push_back(std::move(st));
  }
  return statuses;
}

void DaemonNode::publish_status(Clock::time_point now) {
  std::vector<StreamStatus> statuses = status(now);
  const bool stalled = !healthy(now);
  for (std::size_t i = 0; i < statuses.size(); ++i) {
    StreamStatus& st = statuses[i];
    Stream& s = *streams_[i];
    if (stalled) {
      st.level = 2;
      st.message = "processing stalled";
    } else if (st.counters.dropped > s.reported_dropped) {
      st.level = 1;
      st.message = "falling behind: frames dropped";
    } else if (st.stats.bad_messages > s.reported_bad) {
      st.level = 1;
      st.message = "bad messages received";
    } else if (st.stats.frames_out_of_order > s.reported_out_of_order) {
      st.level = 1;
      st.message = "frames out of order dropped";
    } else if (st.merge && st.merge->missing() > s.reported_missing) {
      st.level = 1;
      st.message = "sensor scans missing from merged frames";
    }
    if (st.merge) s.reported_missing = st.merge->missing();
    s.reported_dropped = st.counters.dropped;
    s.reported_bad = st.stats.bad_messages;
    s.reported_out_of_order = st.stats.frames_out_of_order;
  }
  auto msg = make_status_message(statuses, dds::wall_clock_now());
  status_writer_->write(&msg);
  if (diagnostics_writer_) diagnostics_writer_->write(&msg);
}

std::string DaemonNode::metrics_text(Clock::time_point now) const {
  return daemon_metrics_text(status(now));
}

std::string DaemonNode::summary(Clock::time_point now) const {
  double fps = 0.0;
  std::uint64_t dropped = 0, bad = 0;
  for (const auto& s : streams_) {
    const StatsSnapshot snapshot = s->stats.snapshot(now);
    fps += snapshot.frames_per_second;
    bad += snapshot.bad_messages;
    dropped += scheduler_->counters(s->handle).dropped;
  }
  return fmt::format("{} stream(s), {:.1f} frames/s, {} dropped, {} bad messages", streams_.size(),
                     fps, dropped, bad);
}

DrainResult DaemonNode::shutdown() {
  if (stopped_) return {true, 0, 0};
  stopped_ = true;
  for (auto& s : streams_) {
    detach_reader(*s);
    if (s->zero_copy_reader) {
      s->zero_copy_reader->set_listener(nullptr);
      subscriber_->delete_datareader(s->zero_copy_reader);
      s->zero_copy_reader = nullptr;
    }
    // A merged frame still waiting for a sensor is queued with what arrived.
    if (s->merged) s->merged->flush();
  }
  const auto deadline =
      Clock::now() +
      std::chrono::milliseconds(static_cast<std::int64_t>(config_.shutdown_timeout_s * 1000.0));
  const DrainResult result = scheduler_->drain(
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
  // What is left of the budget goes to the map patches still under repair (reliable writers
  // resend what a lossy link lost): a process that exits at once loses them for the aggregator.
  std::size_t unacknowledged = 0;
  for (auto& s : streams_) {
    if (!s->patch_writer) continue;
    const std::int64_t left_ns = std::max<std::int64_t>(
        0, std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - Clock::now()).count());
    const eprosima::fastrtps::Duration_t wait(static_cast<std::int32_t>(left_ns / 1000000000),
                                              static_cast<std::uint32_t>(left_ns % 1000000000));
    if (s->patch_writer->wait_for_acknowledgments(wait) != ReturnCode_t::RETCODE_OK)
      ++unacknowledged;
  }
  if (unacknowledged > 0)
    spdlog::warn("shut down: map patches of {} stream(s) not acknowledged within {} s",
                 unacknowledged, config_.shutdown_timeout_s);
  publish_status(Clock::now());
  spdlog::info("shut down: {} queued frame(s) dropped{}; {}", result.dropped,
               result.complete ? "" : fmt::format(", {} still in processing", result.in_flight),
               summary());
  return result;
}

}  // namespace litamin2::daemon
