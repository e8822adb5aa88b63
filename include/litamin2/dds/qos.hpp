#pragma once
/// QoS of the product's topics (DESIGN.md section 4 table). Every profile uses Fast DDS's
/// PREALLOCATED_WITH_REALLOC history memory, as samples (scans) have unbounded size.

#include <cstdint>

#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

namespace litamin2::dds {

/// Reader of rt/<stream>/points. Best-effort matches every writer (best-effort and reliable);
/// reliable (to be used when discovery shows a reliable writer, see writer_is_reliable) makes
/// a reliable writer repair lost fragments of large scans. Keep-last `depth`.
eprosima::fastdds::dds::DataReaderQos points_reader_qos(bool reliable = false,
                                                        std::int32_t depth = 10);
/// Reader of a stream's zero-copy input (litamin2_zero_copy/PlainScan, streams[].zero_copy_topic):
/// reliable keep-last `depth` (it matches reliable writers only, so that a slow reader
/// throttles the writer instead of having its loaned samples overwritten), preallocated
/// history, data-sharing automatic (used when the writer is on this host and shares the
/// domain; Fast DDS falls back to its transports otherwise).
eprosima::fastdds::dds::DataReaderQos zero_copy_reader_qos(std::int32_t depth = 10);
/// Writer of a zero-copy input (litamin2-replay --zero-copy): points_writer_qos's reliable
/// keep-all with `depth` samples, preallocated, data-sharing automatic.
eprosima::fastdds::dds::DataWriterQos zero_copy_writer_qos(std::int32_t depth,
                                                           std::int32_t max_blocking_ms);
/// Writer of rt/<stream>/points (the replay tool): reliable keep-all by default, so that a
/// slower reader throttles the writer instead of losing scans (the writer blocks in write()
/// for up to `max_blocking_ms` when its history is full); best_effort: keep-last `depth`.
eprosima::fastdds::dds::DataWriterQos points_writer_qos(bool best_effort = false,
                                                        std::int32_t depth = 10,
                                                        std::int32_t max_blocking_ms = 10000);
/// Heartbeat period of the odometry writers (odom_writer_qos, hence rt/<stream>/odom, the
/// exclusive hot-standby ones, /tf and the aggregator's map-frame odometry). A reliable reader
/// delivers in order, so a message lost on the link holds back every later one until it is
/// resent, and it is resent when the reader's negative acknowledgment answers a heartbeat: with
/// Fast DDS's default period, 3 s, 10 % loss made the odometry arrive in bursts up to 3 s late
/// (docs/deploy.md, the delay test). 0.2 s, two frames at 10 Hz: a lost message is repaired
/// within about 0.2 s plus the round trip. Fast DDS sends periodic heartbeats only while a
/// matched reader has not acknowledged a sample; at 10 Hz that is always, so each writer sends
/// 5 heartbeats/s (instead of 1/3) to each reader and gets as many acknowledgments back, a few
/// dozen bytes each.
inline constexpr std::int32_t kOdometryHeartbeatPeriodMs = 200;
/// Heartbeat period of the map-patch writers (map_patches_writer_qos): a patch lost on the
/// link is resent when the reader's negative acknowledgment answers a heartbeat; with the
/// default 3 s a lost last patch waited longer than litamin2d's shutdown budget (1 s).
inline constexpr std::int32_t kMapPatchHeartbeatPeriodMs = 500;

/// rt/<stream>/odom: reliable, volatile, keep-last `depth`, heartbeat every
/// kOdometryHeartbeatPeriodMs.
eprosima::fastdds::dds::DataWriterQos odom_writer_qos(std::int32_t depth = 100);
eprosima::fastdds::dds::DataReaderQos odom_reader_qos(std::int32_t depth = 100);

/// The latest sample of each of up to `max_instances` instances, kept for late readers:
/// reliable, transient-local, keep-last 1 per instance (the aggregator's corrected poses and
/// map summary per stream, its map tiles per tile). Finite limits: with unlimited ones Fast DDS
/// 2.9 refuses every write, and its default of 10 instances would refuse the 11th.
eprosima::fastdds::dds::DataWriterQos latest_per_instance_writer_qos(std::int32_t max_instances);
eprosima::fastdds::dds::DataReaderQos latest_per_instance_reader_qos(std::int32_t max_instances);
/// rt/litamin2/map_tiles: the latest sample of each of up to 100,000 tiles (a late reader gets
/// every tile's latest).
eprosima::fastdds::dds::DataWriterQos map_tiles_writer_qos();
eprosima::fastdds::dds::DataReaderQos map_tiles_reader_qos();

/// Hot standby (docs/deploy.md, "Hot standby"): a stream's odometry written by several daemons
/// with EXCLUSIVE ownership at `strength` (the owner's the highest), so that a reader takes
/// only the strongest live writer's samples. Fast DDS 2.9 moves a reader to the next writer
/// when the owner's participant is dropped (its lease), not at a writer liveliness lease
/// (measured: a 0.5 s AUTOMATIC writer lease did not shorten the switch below the 2 s
/// participant lease). Readers must be exclusive too (exclusive_odom_reader_qos): a SHARED
/// reader does not match.
eprosima::fastdds::dds::DataWriterQos exclusive_odom_writer_qos(std::uint32_t strength,
                                                                std::int32_t depth = 100);
/// odom_reader_qos with EXCLUSIVE ownership (matches only exclusive writers).
eprosima::fastdds::dds::DataReaderQos exclusive_odom_reader_qos(std::int32_t depth = 100);
/// Any writer QoS made a hot-standby one: EXCLUSIVE ownership at `strength`, or unchanged
/// (SHARED) when `strength` is 0, so that a standby setting of 0 keeps today's behaviour.
eprosima::fastdds::dds::DataWriterQos with_ownership_strength(
    eprosima::fastdds::dds::DataWriterQos qos, std::uint32_t strength);
/// Any reader QoS made EXCLUSIVE: it takes the strongest live writer's samples of each instance
/// (and matches only exclusive writers).
eprosima::fastdds::dds::DataReaderQos exclusive_ownership(
    eprosima::fastdds::dds::DataReaderQos qos);
/// rt/litamin2/map_patches: reliable, transient-local, keep-all per stream instance, any number
/// of streams. The writer holds the latest `history_per_stream` patches of each stream for late
/// readers (an aggregator starting or restarting); when a stream's history is full, writing
/// waits (up to the writer's max_blocking_time, else the write fails) until matched readers
/// have acknowledged its oldest patch, which is then dropped: live readers that keep up lose
/// nothing and memory stays bounded.
eprosima::fastdds::dds::DataWriterQos map_patches_writer_qos(std::int32_t history_per_stream);
/// The reader of the map patches; `fixed_payloads`: PREALLOCATED history memory, so that every
/// sample has a buffer of the type's m_typeSize (+3) and Fast DDS 2.9 drops a sample announced
/// larger before it reserves or reassembles it (ReaderHistory::can_change_be_added_nts), one
/// buffer allocated at start (allocated_samples 1), more on demand.
eprosima::fastdds::dds::DataReaderQos map_patches_reader_qos(bool fixed_payloads = false);
/// rt/litamin2/map_patches read by a daemon only for the latest keyframe id of each stream
/// (sharding's handover): reliable, volatile (no history replayed at match), keep-last 1 per
/// stream instance.
eprosima::fastdds::dds::DataReaderQos map_patch_ids_reader_qos();
/// rt/litamin2/status: reliable, volatile, keep-last `depth`.
eprosima::fastdds::dds::DataWriterQos status_writer_qos(std::int32_t depth = 10);
eprosima::fastdds::dds::DataReaderQos status_reader_qos(std::int32_t depth = 10);
/// rt/diagnostics: as ROS 2's diagnostic_updater creates its /diagnostics publisher
/// (rclcpp::QoS(1): reliable, volatile, keep-last 1).
eprosima::fastdds::dds::DataWriterQos diagnostics_writer_qos();

/// rt/tf: reliable, volatile, keep-last `depth` (tf2_ros::DynamicBroadcasterQoS: depth 100).
eprosima::fastdds::dds::DataWriterQos tf_writer_qos(std::int32_t depth = 100);
eprosima::fastdds::dds::DataReaderQos tf_reader_qos(std::int32_t depth = 100);
/// rt/tf_static: reliable, transient-local, keep-last 1 (tf2_ros::StaticBroadcasterQoS): the
/// one message holds every static transform of the writer, late readers get it. Also the
/// aggregator's map cloud (the latest map for late viewers).
eprosima::fastdds::dds::DataWriterQos tf_static_writer_qos();
eprosima::fastdds::dds::DataReaderQos tf_static_reader_qos();

/// True when a discovered writer offers reliable reliability.
bool writer_is_reliable(const eprosima::fastrtps::rtps::WriterDiscoveryInfo& info);

}  // namespace litamin2::dds
