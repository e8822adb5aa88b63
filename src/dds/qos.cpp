#include "litamin2/dds/qos.hpp"

#include <fastdds/rtps/builtin/data/WriterProxyData.h>

namespace litamin2::dds {

namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

template <typename Qos>
void common(Qos& qos, fdds::ReliabilityQosPolicyKind reliability,
            fdds::DurabilityQosPolicyKind durability, fdds::HistoryQosPolicyKind history,
            std::int32_t depth) {
  qos.reliability().kind = reliability;
  qos.durability().kind = durability;
  qos.history().kind = history;
  qos.history().depth = depth > 0 ? depth : 1;
  qos.endpoint().history_memory_policy = rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
}

/// Keyed keep-all topics (one instance per stream): Fast DDS's default resource limits (10
/// instances, 400 samples per instance, 5000 in all) would refuse the 11th stream's patches.
/// Large finite limits: Fast DDS 2.9 requires max_samples unlimited when the others are, and
/// its keep-all writer then refuses every write.
void unlimited(fdds::ResourceLimitsQosPolicy& limits) {
  limits.max_instances = 10'000;
  limits.max_samples_per_instance = 100'000;
  limits.max_samples = 1'000'000'000;
}

eprosima::fastrtps::Duration_t milliseconds(std::int32_t ms) {
  return eprosima::fastrtps::Duration_t(ms / 1000,
                                        static_cast<std::uint32_t>(ms % 1000) * 1000000u);
}

}  // namespace

fdds::DataReaderQos points_reader_qos(bool reliable, std::int32_t depth) {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, reliable ? fdds::RELIABLE_RELIABILITY_QOS : fdds::BEST_EFFORT_RELIABILITY_QOS,
         fdds::VOLATILE_DURABILITY_QOS, fdds::KEEP_LAST_HISTORY_QOS, depth);
  return qos;
}

fdds::DataWriterQos points_writer_qos(bool best_effort, std::int32_t depth,
                                      std::int32_t max_blocking_ms) {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  if (best_effort) {
    common(qos, fdds::BEST_EFFORT_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
           fdds::KEEP_LAST_HISTORY_QOS, depth);
  } else {
    common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
           fdds::KEEP_ALL_HISTORY_QOS, depth);
    // Keep-all: a full history (max_samples) blocks write() until readers acknowledge.
    qos.resource_limits().max_samples = depth > 0 ? depth : 1;
    qos.resource_limits().max_instances = 1;
    qos.resource_limits().max_samples_per_instance = depth > 0 ? depth : 1;
    qos.resource_limits().allocated_samples = depth > 0 ? depth : 1;
    qos.reliability().max_blocking_time =
        eprosima::fastrtps::Duration_t(max_blocking_ms / 1000, (max_blocking_ms % 1000) * 1000000u);
  }
  return qos;
}

fdds::DataReaderQos zero_copy_reader_qos(std::int32_t depth) {
  fdds::DataReaderQos qos = points_reader_qos(true, depth);
  qos.endpoint().history_memory_policy = rtps::PREALLOCATED_MEMORY_MODE;
  qos.data_sharing().automatic();
  return qos;
}

fdds::DataWriterQos zero_copy_writer_qos(std::int32_t depth, std::int32_t max_blocking_ms) {
  fdds::DataWriterQos qos = points_writer_qos(false, depth, max_blocking_ms);
  qos.endpoint().history_memory_policy = rtps::PREALLOCATED_MEMORY_MODE;
  qos.data_sharing().automatic();
  return qos;
}

fdds::DataWriterQos odom_writer_qos(std::int32_t depth) {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, depth);
  // A lost message holds back the later ones until the next heartbeat gets it resent.
  qos.reliable_writer_qos().times.heartbeatPeriod = milliseconds(kOdometryHeartbeatPeriodMs);
  return qos;
}

fdds::DataReaderQos odom_reader_qos(std::int32_t depth) {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, depth);
  return qos;
}

namespace {

template <typename Qos>
Qos latest_per_instance(Qos qos, std::int32_t max_instances) {
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, 1);
  qos.resource_limits().max_instances = max_instances;
  qos.resource_limits().max_samples_per_instance = 1;
  qos.resource_limits().max_samples = max_instances;
  return qos;
}

}  // namespace

fdds::DataWriterQos latest_per_instance_writer_qos(std::int32_t max_instances) {
  return latest_per_instance(fdds::DATAWRITER_QOS_DEFAULT, max_instances);
}

fdds::DataReaderQos latest_per_instance_reader_qos(std::int32_t max_instances) {
  return latest_per_instance(fdds::DATAREADER_QOS_DEFAULT, max_instances);
}

namespace {
constexpr std::int32_t kMaxMapTiles = 100'000;
}  // namespace

fdds::DataWriterQos map_tiles_writer_qos() {
  return latest_per_instance_writer_qos(kMaxMapTiles);
}

fdds::DataReaderQos map_tiles_reader_qos() {
  return latest_per_instance_reader_qos(kMaxMapTiles);
}

fdds::DataWriterQos exclusive_odom_writer_qos(std::uint32_t strength, std::int32_t depth) {
  fdds::DataWriterQos qos = odom_writer_qos(depth);
  qos.ownership().kind = fdds::EXCLUSIVE_OWNERSHIP_QOS;
  qos.ownership_strength().value = strength;
  return qos;
}

fdds::DataReaderQos exclusive_odom_reader_qos(std::int32_t depth) {
  return exclusive_ownership(odom_reader_qos(depth));
}

fdds::DataWriterQos with_ownership_strength(fdds::DataWriterQos qos, std::uint32_t strength) {
  if (strength == 0) return qos;
  qos.ownership().kind = fdds::EXCLUSIVE_OWNERSHIP_QOS;
  qos.ownership_strength().value = strength;
  return qos;
}

fdds::DataReaderQos exclusive_ownership(fdds::DataReaderQos qos) {
  qos.ownership().kind = fdds::EXCLUSIVE_OWNERSHIP_QOS;
  return qos;
}

fdds::DataWriterQos map_patches_writer_qos(std::int32_t history_per_stream) {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
         fdds::KEEP_ALL_HISTORY_QOS, 1);
  unlimited(qos.resource_limits());
  qos.resource_limits().max_samples_per_instance = history_per_stream > 0 ? history_per_stream : 1;
  // A lost patch waits for the next heartbeat to be resent (kMapPatchHeartbeatPeriodMs).
  qos.reliable_writer_qos().times.heartbeatPeriod = milliseconds(kMapPatchHeartbeatPeriodMs);
  return qos;
}

fdds::DataReaderQos map_patches_reader_qos(bool fixed_payloads) {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
         fdds::KEEP_ALL_HISTORY_QOS, 1);
  unlimited(qos.resource_limits());
  if (fixed_payloads) {
    qos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_MEMORY_MODE;
    qos.resource_limits().allocated_samples = 1;
  }
  return qos;
}

fdds::DataReaderQos map_patch_ids_reader_qos() {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, 1);
  return qos;
}

// rt/tf has the odometry's QoS (reliable, volatile, keep last), as tf2_ros's broadcaster does.
fdds::DataWriterQos tf_writer_qos(std::int32_t depth) {
  return odom_writer_qos(depth);
}

fdds::DataReaderQos tf_reader_qos(std::int32_t depth) {
  return odom_reader_qos(depth);
}

fdds::DataWriterQos tf_static_writer_qos() {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, 1);
  return qos;
}

fdds::DataReaderQos tf_static_reader_qos() {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, 1);
  return qos;
}

fdds::DataWriterQos status_writer_qos(std::int32_t depth) {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, depth);
  return qos;
}

fdds::DataWriterQos diagnostics_writer_qos() {
  return status_writer_qos(1);
}

fdds::DataReaderQos status_reader_qos(std::int32_t depth) {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  common(qos, fdds::RELIABLE_RELIABILITY_QOS, fdds::VOLATILE_DURABILITY_QOS,
         fdds::KEEP_LAST_HISTORY_QOS, depth);
  return qos;
}

bool writer_is_reliable(const rtps::WriterDiscoveryInfo& info) {
  return info.info.m_qos.m_reliability.kind == fdds::RELIABLE_RELIABILITY_QOS;
}

}  // namespace litamin2::dds
