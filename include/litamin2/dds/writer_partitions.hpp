#pragma once
/// The partitions of every discovered remote writer of one topic, by writer GUID, as Fast DDS's
/// discovery announces them; a DomainParticipantListener (pass it to create_participant). Fast
/// DDS 2.9 calls on_publisher_discovery (PDP::addWriterProxyData) before it matches the writer
/// with a local reader (EDP::pairing_writer_proxy_with_any_local_reader), so a sample's writer
/// is known when the sample arrives; a QoS change (CHANGED_QOS_WRITER) replaces the entry.
/// DataReader::get_matched_publication_data, the standard way, returns RETCODE_UNSUPPORTED in
/// 2.9. Thread-safe: discovery writes from Fast DDS's event thread, listeners read.

#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::dds {

class WriterPartitions : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  /// Records the writers of `topic` only.
  explicit WriterPartitions(std::string topic) : topic_(std::move(topic)) {}

  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;

  /// The partitions of the writer whose handle is `publication_handle` (SampleInfo's); none if
  /// the writer is unknown (never discovered, or removed since).
  std::optional<std::vector<std::string>> find(
      const eprosima::fastrtps::rtps::InstanceHandle_t& publication_handle) const;
  /// Writers known.
  std::size_t size() const;

 private:
  using Key = std::array<std::uint8_t, 16>;
  static Key key(const eprosima::fastrtps::rtps::InstanceHandle_t& handle);

  const std::string topic_;
  mutable std::mutex mutex_;
  std::map<Key, std::vector<std::string>> writers_;
};

}  // namespace litamin2::dds
